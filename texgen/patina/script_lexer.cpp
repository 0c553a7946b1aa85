#include "texgen/patina/script_lexer.h"

#include <charconv>
#include <cmath>

namespace patina::texgen {

namespace {

bool is_letter(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Walks the text keeping the line and column of the next character.
class Cursor {
public:
    explicit Cursor(std::string_view text) : text_(text) {}

    bool done() const { return pos_ >= text_.size(); }
    char peek(size_t ahead = 0) const
    {
        return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
    }
    SourceLocation location() const { return {line_, column_}; }
    size_t position() const { return pos_; }

    char advance()
    {
        const char c = text_[pos_++];
        if (c == '\n') {
            ++line_;
            column_ = 1;
        } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
            // A UTF-8 continuation byte belongs to the character before it.
            ++column_;
        }
        return c;
    }

private:
    std::string_view text_;
    size_t pos_ = 0;
    int line_ = 1;
    int column_ = 1;
};

Token make(TokenKind kind, std::string text, SourceLocation location)
{
    Token token;
    token.kind = kind;
    token.text = std::move(text);
    token.location = location;
    return token;
}

Token lex_number(Cursor& in, std::string_view text, const std::string& file_name)
{
    const SourceLocation start = in.location();
    const size_t begin = in.position();
    // Take the whole run of letters, digits and dots (and a sign after an exponent's 'e'), so
    // that "1.2.3" and "10x" are one bad number rather than a number and a surprise.
    while (!in.done()) {
        const char c = in.peek();
        const char previous = in.position() > begin ? text[in.position() - 1] : '\0';
        const bool exponent_sign = (c == '+' || c == '-') && (previous == 'e' || previous == 'E') &&
                                   is_digit(text[begin]);
        if (!(is_letter(c) || is_digit(c) || c == '.' || exponent_sign))
            break;
        in.advance();
    }
    const std::string_view digits = text.substr(begin, in.position() - begin);
    Token token = make(TokenKind::Number, std::string(digits), start);
    const auto [end, error] =
        std::from_chars(digits.data(), digits.data() + digits.size(), token.number);
    if (error != std::errc() || end != digits.data() + digits.size() ||
        !std::isfinite(token.number))
        throw ScriptError(file_name, start, "bad number '" + std::string(digits) + "'");
    token.is_integer = digits.find_first_not_of("0123456789") == std::string_view::npos;
    return token;
}

Token lex_string(Cursor& in, const std::string& file_name)
{
    const SourceLocation start = in.location();
    in.advance();  // the opening quote
    std::string value;
    while (true) {
        if (in.done() || in.peek() == '\n')
            throw ScriptError(file_name, start, "string is not closed on its line");
        const char c = in.advance();
        if (c == '"')
            break;
        if (c != '\\') {
            value += c;
            continue;
        }
        const SourceLocation escape = in.location();
        const char e = in.done() ? '\0' : in.advance();
        switch (e) {
        case '"': value += '"'; break;
        case '\\': value += '\\'; break;
        case 'n': value += '\n'; break;
        case 't': value += '\t'; break;
        default:
            throw ScriptError(file_name, escape,
                              std::string("unknown escape '\\") + e + "' in a string");
        }
    }
    Token token = make(TokenKind::String, std::move(value), start);
    return token;
}

}  // namespace

std::vector<Token> tokenize(std::string_view text, const std::string& file_name)
{
    std::vector<Token> tokens;
    Cursor in(text);
    while (!in.done()) {
        const char c = in.peek();
        const SourceLocation at = in.location();
        if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            in.advance();
        } else if (c == '\n') {
            tokens.push_back(make(TokenKind::Newline, "\n", at));
            in.advance();
        } else if (c == '#' || (c == '/' && in.peek(1) == '/')) {
            while (!in.done() && in.peek() != '\n')
                in.advance();
        } else if (is_letter(c)) {
            std::string word;
            while (!in.done() && (is_letter(in.peek()) || is_digit(in.peek())))
                word += in.advance();
            tokens.push_back(make(TokenKind::Word, std::move(word), at));
        } else if (is_digit(c) || (c == '.' && is_digit(in.peek(1)))) {
            tokens.push_back(lex_number(in, text, file_name));
        } else if (c == '"') {
            tokens.push_back(lex_string(in, file_name));
        } else {
            TokenKind kind;
            switch (c) {
            case '(': kind = TokenKind::LeftParen; break;
            case ')': kind = TokenKind::RightParen; break;
            case ',': kind = TokenKind::Comma; break;
            case ';': kind = TokenKind::Semicolon; break;
            case '=': kind = TokenKind::Equals; break;
            case '+': kind = TokenKind::Plus; break;
            case '-': kind = TokenKind::Minus; break;
            case '*': kind = TokenKind::Star; break;
            case '/': kind = TokenKind::Slash; break;
            default: {
                // Name the whole UTF-8 character, not its first byte.
                std::string character(1, in.advance());
                while (!in.done() && (static_cast<unsigned char>(in.peek()) & 0xC0) == 0x80)
                    character += in.advance();
                throw ScriptError(file_name, at, "unexpected character '" + character + "'");
            }
            }
            tokens.push_back(make(kind, std::string(1, in.advance()), at));
        }
    }
    tokens.push_back(make(TokenKind::End, "", in.location()));
    return tokens;
}

std::string describe(const Token& token)
{
    switch (token.kind) {
    case TokenKind::Newline: return "end of line";
    case TokenKind::End: return "end of file";
    case TokenKind::String: return "string \"" + token.text + "\"";
    default: return "'" + token.text + "'";
    }
}

}  // namespace patina::texgen
