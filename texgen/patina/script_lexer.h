// The tokens of the patina script language (D&H 1996 §3.2, §5.1). Words, numbers, strings
// and punctuation; a line break is a token of its own because a statement ends at the end of
// its line as well as at ';' (the paper's marine script has a statement without ';'). '#' and
// '//' start a comment that runs to the end of the line.
#pragma once

#include "texgen/patina/script_error.h"

#include <string>
#include <string_view>
#include <vector>

namespace patina::texgen {

enum class TokenKind {
    Word,        ///< [A-Za-z_][A-Za-z0-9_]*: keywords, material words, names
    Number,      ///< a decimal number without sign: 3, 0.35, .5, 1e-3
    String,      ///< "..." with \" \\ \n \t escapes; text holds the decoded contents
    LeftParen,   ///< (
    RightParen,  ///< )
    Comma,       ///< ,
    Semicolon,   ///< ;
    Equals,      ///< =
    Plus,        ///< +
    Minus,       ///< -
    Star,        ///< *
    Slash,       ///< /
    Newline,     ///< the end of a line (comments removed)
    End,         ///< the end of the script
};

struct Token {
    TokenKind kind = TokenKind::End;
    std::string text;         ///< as written (decoded for a String)
    double number = 0;        ///< the value of a Number
    bool is_integer = false;  ///< a Number written with digits only ("3", not "3.0")
    SourceLocation location;  ///< of the token's first character
};

/// Reads the tokens of a script one at a time, so that the parser meets an error in the
/// order of the text: a bad character late in a line does not hide a syntax error before it.
class Lexer {
public:
    /// `text` must outlive the lexer; `file_name` names it in messages.
    Lexer(std::string_view text, std::string file_name);

    /// The next token; End at the end of the text, and again on every later call. Throws
    /// ScriptError "FILE:LINE:COL: error: ..." for a character that starts no token, a bad
    /// number ("1.2.3", "10x") and a string that is not closed on its line.
    Token next();

private:
    bool done() const { return pos_ >= text_.size(); }
    char peek(size_t ahead = 0) const;
    char advance();
    SourceLocation location() const { return {line_, column_}; }
    Token lex_number();
    Token lex_string();

    std::string_view text_;
    std::string file_name_;
    size_t pos_ = 0;
    int line_ = 1;
    int column_ = 1;
};

/// All the tokens of `text`, ending with one End token (Lexer::next until End).
std::vector<Token> tokenize(std::string_view text, const std::string& file_name);

/// How a token is named in a message: "'coat'", "';'", "string \"a.exr\"", "end of line",
/// "end of file".
std::string describe(const Token& token);

}  // namespace patina::texgen
