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

// A UTF-8 continuation byte belongs to the character before it.
bool is_continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

Token make(TokenKind kind, std::string text, SourceLocation location)
{
    Token token;
    token.kind = kind;
    token.text = std::move(text);
    token.location = location;
    return token;
}

}  // namespace

Lexer::Lexer(std::string_view text, std::string file_name)
    : text_(text), file_name_(std::move(file_name))
{
}

char Lexer::peek(size_t ahead) const
{
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
}

char Lexer::advance()
{
    const char c = text_[pos_++];
    if (c == '\n') {
        ++line_;
        column_ = 1;
    } else if (!is_continuation(c)) {
        ++column_;
    }
    return c;
}

Token Lexer::next()
{
    while (!done()) {
        const char c = peek();
        const SourceLocation at = location();
        if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            advance();
        } else if (c == '\n') {
            advance();
            return make(TokenKind::Newline, "\n", at);
        } else if (c == '#' || (c == '/' && peek(1) == '/')) {
            while (!done() && peek() != '\n')
                advance();
        } else if (is_letter(c)) {
            std::string word;
            while (!done() && (is_letter(peek()) || is_digit(peek())))
                word += advance();
            return make(TokenKind::Word, std::move(word), at);
        } else if (is_digit(c) || (c == '.' && is_digit(peek(1)))) {
            return lex_number();
        } else if (c == '"') {
            return lex_string();
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
                std::string character(1, advance());
                while (!done() && is_continuation(peek()))
                    character += advance();
                throw ScriptError(file_name_, at, "unexpected character '" + character + "'");
            }
            }
            return make(kind, std::string(1, advance()), at);
        }
    }
    return make(TokenKind::End, "", location());
}

Token Lexer::lex_number()
{
    const SourceLocation start = location();
    const size_t begin = pos_;
    // Take the whole run of letters, digits and dots (and a sign after an exponent's 'e'), so
    // that "1.2.3" and "10x" are one bad number rather than a number and a surprise.
    while (!done()) {
        const char c = peek();
        const char previous = pos_ > begin ? text_[pos_ - 1] : '\0';
        const bool exponent_sign = (c == '+' || c == '-') && (previous == 'e' || previous == 'E') &&
                                   is_digit(text_[begin]);
        if (!(is_letter(c) || is_digit(c) || c == '.' || exponent_sign))
            break;
        advance();
    }
    const std::string_view digits = text_.substr(begin, pos_ - begin);
    Token token = make(TokenKind::Number, std::string(digits), start);
    const auto [end, error] =
        std::from_chars(digits.data(), digits.data() + digits.size(), token.number);
    if (error != std::errc() || end != digits.data() + digits.size() ||
        !std::isfinite(token.number))
        throw ScriptError(file_name_, start, "bad number '" + std::string(digits) + "'");
    token.is_integer = digits.find_first_not_of("0123456789") == std::string_view::npos;
    return token;
}

Token Lexer::lex_string()
{
    const SourceLocation start = location();
    advance();  // the opening quote
    std::string value;
    while (true) {
        if (done() || peek() == '\n')
            throw ScriptError(file_name_, start, "string is not closed on its line");
        const SourceLocation at = location();
        const char c = advance();
        if (c == '"')
            break;
        if (c != '\\') {
            value += c;
            continue;
        }
        const char e = done() ? '\0' : advance();
        switch (e) {
        case '"': value += '"'; break;
        case '\\': value += '\\'; break;
        case 'n': value += '\n'; break;
        case 't': value += '\t'; break;
        default:
            throw ScriptError(file_name_, at,
                              std::string("unknown escape '\\") + e + "' in a string");
        }
    }
    return make(TokenKind::String, std::move(value), start);
}

std::vector<Token> tokenize(std::string_view text, const std::string& file_name)
{
    Lexer lexer(text, file_name);
    std::vector<Token> tokens;
    do {
        tokens.push_back(lexer.next());
    } while (tokens.back().kind != TokenKind::End);
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
