#include "texgen/patina/script_parser.h"

#include "texgen/patina/script_lexer.h"
#include "texgen/patina/script_names.h"

#include <algorithm>
#include <deque>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

namespace patina::texgen {

namespace {

// A number with its optional leading '-', as an amount, a curve point or a parameter.
struct SignedNumber {
    double value = 0;
    bool is_integer = false;  // digits only and no sign
    std::string text;         // as written, sign included
    SourceLocation location;  // of the sign, or of the digits
};

// A material name and the amount after it (thickness, height or radius).
struct MaterialAmount {
    std::string material;
    SourceLocation material_location;
    double amount = 0;
};

struct Declaration {
    NameKind kind = NameKind::Let;
    SourceLocation location;
};

const char* kind_name(NameKind kind)
{
    switch (kind) {
    case NameKind::Let: return "let";
    case NameKind::Curve: return "curve";
    case NameKind::Map: return "map";
    case NameKind::Field: return "built-in field";
    }
    return "name";
}

class Parser {
public:
    Parser(std::string_view text, const std::string& file_name,
           const std::set<std::string>& material_names)
        : lexer_(text, file_name), file_name_(file_name), materials_(material_names),
          material_list_(material_names.begin(), material_names.end())
    {
    }

    Script parse()
    {
        Script script;
        script.file_name = file_name_;
        while (true) {
            const Token& token = peek();
            if (token.kind == TokenKind::End)
                break;
            if (token.kind == TokenKind::Newline || token.kind == TokenKind::Semicolon) {
                next();
                continue;
            }
            if (render_)
                fail(token.location, describe(token) + " after 'render maps' (at " +
                                         to_string(*render_) +
                                         "), which must be the last statement");
            const std::string keyword = token.kind == TokenKind::Word ? token.text : "";
            script.statements.push_back(parse_statement());
            expect_statement_end(keyword);
        }
        return script;
    }

private:
    // --- Tokens ----------------------------------------------------------------------------

    // Token i of the script, read from the lexer when first needed (so that errors come in
    // the order of the text); the End token for every i past the end.
    const Token& token_at(size_t i)
    {
        while (tokens_.size() <= i) {
            if (!tokens_.empty() && tokens_.back().kind == TokenKind::End)
                return tokens_.back();
            tokens_.push_back(lexer_.next());
        }
        return tokens_[i];
    }

    // The next token; inside parentheses line breaks are skipped (a statement continues).
    const Token& peek()
    {
        while (depth_ > 0 && token_at(pos_).kind == TokenKind::Newline)
            ++pos_;
        return token_at(pos_);
    }

    // The token after peek(), without skipping line breaks.
    const Token& peek_second()
    {
        peek();
        return token_at(pos_ + 1);
    }

    Token next()
    {
        Token token = peek();
        if (token.kind != TokenKind::End)
            ++pos_;
        return token;
    }

    bool at(TokenKind kind) { return peek().kind == kind; }

    bool at_statement_end()
    {
        const TokenKind kind = peek().kind;
        return kind == TokenKind::Semicolon || kind == TokenKind::Newline ||
               kind == TokenKind::End;
    }

    [[noreturn]] void fail(SourceLocation location, const std::string& message) const
    {
        throw ScriptError(file_name_, location, message);
    }

    [[noreturn]] void fail_unexpected(const std::string& expected)
    {
        const Token& token = peek();
        if (token.kind == TokenKind::RightParen && depth_ == 0)
            fail(token.location, "unbalanced parenthesis: ')' without a matching '('");
        std::string message = "expected " + expected + ", found " + describe(token);
        // A line that ends in an operator was probably meant to go on.
        const TokenKind previous = pos_ > 0 ? tokens_[pos_ - 1].kind : TokenKind::End;
        if (token.kind == TokenKind::Newline &&
            (previous == TokenKind::Plus || previous == TokenKind::Minus ||
             previous == TokenKind::Star || previous == TokenKind::Slash))
            message += " (a statement ends at the end of its line; wrap a long expression in "
                       "parentheses to continue it)";
        fail(token.location, message);
    }

    // Consume '(' and enter it: line breaks no longer end the statement.
    SourceLocation open_paren(const std::string& expected)
    {
        if (!at(TokenKind::LeftParen))
            fail_unexpected(expected);
        ++depth_;
        return next().location;
    }

    void close_paren(SourceLocation open)
    {
        if (!at(TokenKind::RightParen))
            fail_unexpected("')' to close the '(' at " + to_string(open));
        --depth_;
        next();
    }

    void expect_statement_end(const std::string& keyword)
    {
        if (at(TokenKind::Semicolon) || at(TokenKind::Newline)) {
            next();
            return;
        }
        if (at(TokenKind::End))
            return;
        fail_unexpected("';' or end of line after the " + keyword + " statement");
    }

    std::optional<SignedNumber> take_number()
    {
        const Token& first = peek();
        const bool negative =
            first.kind == TokenKind::Minus && peek_second().kind == TokenKind::Number;
        if (first.kind != TokenKind::Number && !negative)
            return std::nullopt;
        SignedNumber number;
        number.location = first.location;
        if (negative)
            next();
        const Token digits = next();
        number.value = negative ? -digits.number : digits.number;
        number.is_integer = digits.is_integer && !negative;
        number.text = (negative ? "-" : "") + digits.text;
        return number;
    }

    SignedNumber expect_number(const std::string& what)
    {
        std::optional<SignedNumber> number = take_number();
        if (!number)
            fail_unexpected(what);
        return *number;
    }

    // An amount that may not be negative (D&H 1996 §3.2: thicknesses, heights, radii).
    double non_negative(const SignedNumber& number, const std::string& what) const
    {
        if (number.value < 0)
            fail(number.location, "negative " + what + " " + number.text);
        return number.value;
    }

    void expect_word(const std::string& word, const std::string& context)
    {
        if (!at(TokenKind::Word) || peek().text != word)
            fail_unexpected("'" + word + "' " + context);
        next();
    }

    // --- Statements ------------------------------------------------------------------------

    Statement parse_statement()
    {
        const Token& token = peek();
        if (token.kind != TokenKind::Word)
            fail_unexpected("an operator (new, coat, erode, fill, polish, offset, render, map, "
                            "curve or let)");
        const std::string& word = token.text;
        if (word == "new")
            return parse_new();
        if (word == "coat")
            return parse_coat();
        if (word == "erode")
            return parse_erode();
        if (word == "fill")
            return parse_fill();
        if (word == "polish")
            return parse_polish();
        if (word == "offset")
            return parse_offset();
        if (word == "render")
            return parse_render();
        if (word == "map")
            return parse_map();
        if (word == "curve")
            return parse_curve();
        if (word == "let")
            return parse_let();
        fail(token.location,
             "unknown operator '" + word + "'" + did_you_mean(word, operator_keywords()));
    }

    NewStatement parse_new()
    {
        NewStatement s;
        s.location = next().location;
        std::vector<std::string> words = material_words("new");
        std::string name = join(words);
        if (at(TokenKind::Number) && peek().is_integer)
            name += " " + next().text;  // the stage number of "marine patina 3"
        s.material = resolve_material(name, words_location_);
        return s;
    }

    CoatStatement parse_coat()
    {
        CoatStatement s;
        s.location = next().location;
        const MaterialAmount m = material_and_amount("coat", "thickness");
        s.material = m.material;
        s.material_location = m.material_location;
        s.thickness_um = m.amount;
        s.map = optional_map();
        return s;
    }

    ErodeStatement parse_erode()
    {
        ErodeStatement s;
        s.location = next().location;
        s.thickness_um = non_negative(expect_number("a thickness (µm) after 'erode'"),
                                      "thickness");
        s.map = optional_map();
        return s;
    }

    FillStatement parse_fill()
    {
        FillStatement s;
        s.location = next().location;
        const MaterialAmount m = material_and_amount("fill", "height");
        s.material = m.material;
        s.material_location = m.material_location;
        s.height_um = m.amount;
        s.map = optional_map();
        return s;
    }

    PolishStatement parse_polish()
    {
        PolishStatement s;
        s.location = next().location;
        if (at(TokenKind::Word) && peek().text == "until") {
            next();
            s.mode = PolishStatement::Mode::UntilExposed;
            const SignedNumber fraction =
                expect_number("the fraction of area to expose (0 to 1) after 'until'");
            if (fraction.value < 0 || fraction.value > 1)
                fail(fraction.location,
                     "exposed fraction " + fraction.text + " is not between 0 and 1");
            s.exposed_fraction = fraction.value;
            expect_word("exposed", "after the fraction of 'polish until'");
            return s;
        }
        s.height_um = non_negative(
            expect_number("a height (µm) or 'until' after 'polish'"), "height");
        s.map = optional_map();
        return s;
    }

    OffsetStatement parse_offset()
    {
        OffsetStatement s;
        s.location = next().location;
        const MaterialAmount m = material_and_amount("offset", "radius");
        s.material = m.material;
        s.material_location = m.material_location;
        s.radius_m = m.amount;
        if (at(TokenKind::Word)) {
            static const std::vector<std::string> kVariants = {"tangent", "closing"};
            const Token variant = next();
            if (variant.text == "tangent")
                s.variant = OffsetStatement::Variant::Tangent;
            else if (variant.text == "closing")
                s.variant = OffsetStatement::Variant::Closing;
            else
                fail(variant.location, "unknown offset variant '" + variant.text +
                                           "', expected 'tangent' or 'closing'" +
                                           did_you_mean(variant.text, kVariants));
        }
        return s;
    }

    RenderStatement parse_render()
    {
        RenderStatement s;
        s.location = next().location;
        expect_word("maps", "after 'render'");
        render_ = s.location;
        return s;
    }

    MapStatement parse_map()
    {
        MapStatement s;
        s.location = next().location;
        const Token name = declared_name("map");
        s.name = name.text;
        if (!at(TokenKind::Equals))
            fail_unexpected("'=' after 'map " + s.name + "'");
        next();
        if (at(TokenKind::Word) && peek().text == "material") {
            next();
            if (!at(TokenKind::String))
                fail_unexpected("the mesh material of map '" + s.name + "' (a \"quoted\" name)");
            s.material = next().text;
            if (s.material.empty())
                fail(s.location, "empty material name for map '" + s.name + "'");
            declare(name, NameKind::Map);
            return s;
        }
        if (!at(TokenKind::String))
            fail_unexpected("the file of map '" + s.name + "' (a \"quoted\" path)");
        const Token path = next();
        if (path.text.empty())
            fail(path.location, "empty file name for map '" + s.name + "'");
        s.path = path.text;
        if (at(TokenKind::String))
            s.channel = next().text;
        declare(name, NameKind::Map);
        return s;
    }

    CurveStatement parse_curve()
    {
        CurveStatement s;
        s.location = next().location;
        const Token name = declared_name("curve");
        s.name = name.text;
        if (!at(TokenKind::Equals))
            fail_unexpected("'=' after 'curve " + s.name + "'");
        next();
        const SourceLocation open = open_paren("'(' to start the points of curve '" + s.name + "'");
        std::string previous_time;
        while (true) {
            const SignedNumber time = expect_number("a time (years) in curve '" + s.name + "'");
            const SignedNumber value =
                expect_number("the value at time " + time.text + " of curve '" + s.name + "'");
            if (!s.points.empty() && time.value <= s.points.back().time_years)
                fail(time.location, "curve '" + s.name + "': time " + time.text +
                                        " does not follow " + previous_time +
                                        " (times must ascend)");
            s.points.push_back({time.value, value.value});
            previous_time = time.text;
            if (at(TokenKind::Comma)) {
                next();
                continue;
            }
            if (!at(TokenKind::RightParen))
                fail_unexpected("',' or ')' to close the '(' at " + to_string(open));
            close_paren(open);
            break;
        }
        declare(name, NameKind::Curve);
        return s;
    }

    LetStatement parse_let()
    {
        LetStatement s;
        s.location = next().location;
        const Token name = declared_name("let");
        s.name = name.text;
        if (!at(TokenKind::Equals))
            fail_unexpected("'=' after 'let " + s.name + "'");
        next();
        s.value = parse_expr();
        // Declared after its expression: a let cannot refer to itself.
        declare(name, NameKind::Let);
        return s;
    }

    // --- Materials -------------------------------------------------------------------------

    static std::string join(const std::vector<std::string>& words)
    {
        std::string text;
        for (const std::string& word : words)
            text += (text.empty() ? "" : " ") + word;
        return text;
    }

    // The words of a material name; sets words_location_ to the first.
    std::vector<std::string> material_words(const std::string& keyword)
    {
        if (!at(TokenKind::Word))
            fail_unexpected("a material name after '" + keyword + "'");
        words_location_ = peek().location;
        std::vector<std::string> words;
        while (at(TokenKind::Word))
            words.push_back(next().text);
        return words;
    }

    bool known(const std::string& name) const { return materials_.count(name) > 0; }

    std::string resolve_material(const std::string& name, SourceLocation location) const
    {
        if (!known(name))
            fail(location,
                 "unknown material '" + name + "'" + did_you_mean(name, material_list_));
        return name;
    }

    // MATERIAL AMOUNT: the words up to the first number; a whole first number followed by a
    // second number is the material's stage (script_parser.h, "Material names").
    MaterialAmount material_and_amount(const std::string& keyword, const std::string& amount)
    {
        MaterialAmount result;
        const std::string words = join(material_words(keyword));
        result.material_location = words_location_;
        const std::optional<SignedNumber> first = take_number();
        if (!first) {
            if (!known(words))
                resolve_material(words, result.material_location);
            fail_unexpected("a " + amount + " after the material '" + words + "'");
        }
        // Look at the second number without taking it.
        const size_t after_first = pos_;
        const std::optional<SignedNumber> second = take_number();
        pos_ = after_first;
        const std::string staged = words + " " + first->text;
        if (first->is_integer && second && (known(staged) || !known(words))) {
            result.material = resolve_material(staged, result.material_location);
            take_number();
            result.amount = non_negative(*second, amount);
            return result;
        }
        if (!known(words) && first->is_integer && known(staged))
            fail_unexpected("a " + amount + " after the material '" + staged + "'");
        result.material = resolve_material(words, result.material_location);
        result.amount = non_negative(*first, amount);
        return result;
    }

    // --- Names -----------------------------------------------------------------------------

    // The NAME of a map, curve or let: a word that is not taken.
    Token declared_name(const std::string& keyword)
    {
        if (!at(TokenKind::Word))
            fail_unexpected("a name after '" + keyword + "'");
        const Token name = next();
        const std::string& word = name.text;
        const auto& keywords = operator_keywords();
        if (std::find(keywords.begin(), keywords.end(), word) != keywords.end() ||
            word == "texture")
            fail(name.location, "'" + word + "' is a keyword and cannot name a " + keyword);
        if (find_builtin_field(word))
            fail(name.location, "'" + word + "' is a built-in field and cannot name a " + keyword);
        if (find_builtin_function(word))
            fail(name.location, "'" + word + "' is a function and cannot name a " + keyword);
        if (const auto it = declared_.find(word); it != declared_.end())
            fail(name.location, "'" + word + "' is already declared as a " +
                                    kind_name(it->second.kind) + " at " +
                                    to_string(it->second.location));
        return name;
    }

    void declare(const Token& name, NameKind kind)
    {
        declared_[name.text] = Declaration{kind, name.location};
    }

    std::vector<std::string> visible_names() const
    {
        std::vector<std::string> names;
        for (const auto& [name, declaration] : declared_)
            names.push_back(name);
        for (const BuiltinField& field : builtin_fields())
            names.emplace_back(field.name);
        return names;
    }

    // --- Expressions -----------------------------------------------------------------------

    std::optional<Expr> optional_map()
    {
        if (at_statement_end())
            return std::nullopt;
        return parse_expr();
    }

    Expr node(ExprKind kind, SourceLocation location, std::vector<Expr> operands = {}) const
    {
        Expr expr;
        expr.kind = kind;
        expr.location = location;
        expr.operands = std::move(operands);
        for (const Expr& operand : expr.operands)
            expr.depth = std::max(expr.depth, operand.depth + 1);
        if (expr.depth > kMaxExpressionDepth)
            fail_too_deep(location);
        return expr;
    }

    [[noreturn]] void fail_too_deep(SourceLocation location) const
    {
        fail(location, "expression nested more than " + std::to_string(kMaxExpressionDepth) +
                           " levels deep (parentheses, minus signs or a chain of operators); "
                           "split it into smaller expressions");
    }

    /// Counts the parser's own recursion (parentheses and minus signs open before any node
    /// is built), so that it is refused before it can overflow the stack.
    class Nesting {
    public:
        explicit Nesting(Parser& parser) : parser_(parser)
        {
            if (++parser_.nesting_ > kMaxExpressionDepth)
                parser_.fail_too_deep(parser_.peek().location);
        }
        ~Nesting() { --parser_.nesting_; }
        Nesting(const Nesting&) = delete;
        Nesting& operator=(const Nesting&) = delete;

    private:
        Parser& parser_;
    };

    Expr parse_expr()
    {
        const Nesting nesting(*this);
        Expr left = parse_term();
        while (at(TokenKind::Plus) || at(TokenKind::Minus)) {
            const Token op = next();
            Expr right = parse_term();
            left = node(op.kind == TokenKind::Plus ? ExprKind::Add : ExprKind::Subtract,
                        op.location, {std::move(left), std::move(right)});
        }
        return left;
    }

    Expr parse_term()
    {
        Expr left = parse_unary();
        while (at(TokenKind::Star) || at(TokenKind::Slash)) {
            const Token op = next();
            Expr right = parse_unary();
            left = node(op.kind == TokenKind::Star ? ExprKind::Multiply : ExprKind::Divide,
                        op.location, {std::move(left), std::move(right)});
        }
        return left;
    }

    Expr parse_unary()
    {
        if (at(TokenKind::Minus)) {
            const Nesting nesting(*this);
            const SourceLocation location = next().location;
            std::vector<Expr> operand;
            operand.push_back(parse_unary());
            return node(ExprKind::Negate, location, std::move(operand));
        }
        return parse_primary();
    }

    Expr parse_primary()
    {
        const Token& token = peek();
        if (token.kind == TokenKind::Number) {
            Expr expr = node(ExprKind::Number, token.location);
            expr.number = next().number;
            return expr;
        }
        if (token.kind == TokenKind::LeftParen) {
            const SourceLocation open = open_paren("'('");
            Expr inner = parse_expr();
            close_paren(open);
            return inner;
        }
        if (token.kind != TokenKind::Word)
            fail_unexpected("an expression");
        const Token word = next();
        if (at(TokenKind::LeftParen)) {
            if (word.text == "texture")
                return parse_texture(word.location);
            return parse_call(word);
        }
        if (word.text == "texture")
            fail_unexpected("'(' after 'texture' (texture(MODEL RATE STEP TOTAL))");
        Expr expr = node(ExprKind::Name, word.location);
        expr.name = word.text;
        if (const auto it = declared_.find(word.text); it != declared_.end())
            expr.name_kind = it->second.kind;
        else if (find_builtin_field(word.text))
            expr.name_kind = NameKind::Field;
        else
            fail(word.location,
                 "unknown name '" + word.text + "'" + did_you_mean(word.text, visible_names()));
        return expr;
    }

    Expr parse_call(const Token& word)
    {
        const BuiltinFunction* function = find_builtin_function(word.text);
        if (!function) {
            if (const auto it = declared_.find(word.text); it != declared_.end())
                fail(word.location, "'" + word.text + "' is a " + kind_name(it->second.kind) +
                                        ", not a function");
            if (find_builtin_field(word.text))
                fail(word.location, "'" + word.text + "' is a built-in field, not a function");
            std::vector<std::string> functions = {"texture"};
            for (const BuiltinFunction& f : builtin_functions())
                functions.emplace_back(f.name);
            fail(word.location,
                 "unknown function '" + word.text + "'" + did_you_mean(word.text, functions));
        }
        const SourceLocation open = open_paren("'('");
        std::vector<Expr> arguments;
        if (!at(TokenKind::RightParen)) {
            arguments.push_back(parse_expr());
            while (at(TokenKind::Comma)) {
                next();
                arguments.push_back(parse_expr());
            }
        }
        close_paren(open);
        Expr call = node(ExprKind::Call, word.location, std::move(arguments));
        call.name = word.text;
        if (static_cast<int>(call.operands.size()) != function->arity)
            fail(word.location, word.text + " takes " + std::to_string(function->arity) +
                                    " argument" + (function->arity == 1 ? "" : "s") +
                                    ", found " + std::to_string(call.operands.size()));
        return call;
    }

    std::string texture_name(std::span<const std::string> names, const std::string& what)
    {
        std::string expected = "a growth " + what + " (";
        for (size_t i = 0; i < names.size(); ++i)
            expected += (i > 0 ? ", " : "") + names[i];
        expected += ")";
        if (!at(TokenKind::Word))
            fail_unexpected(expected + " in texture(...)");
        const Token word = next();
        if (std::find(names.begin(), names.end(), word.text) == names.end())
            fail(word.location, "unknown growth " + what + " '" + word.text + "'" +
                                    did_you_mean(word.text, names));
        return word.text;
    }

    int texture_count(const std::string& what)
    {
        const SignedNumber number = expect_number("the " + what + " in texture(...)");
        if (!number.is_integer || number.value > 1e9)
            fail(number.location,
                 "the " + what + " " + number.text + " is not a whole number >= 0");
        return static_cast<int>(number.value);
    }

    Expr parse_texture(SourceLocation location)
    {
        Expr expr = node(ExprKind::Texture, location);
        TextureCall& t = expr.texture;
        const SourceLocation open = open_paren("'('");
        t.model = texture_name(texture_model_names(), "model");
        t.rate = texture_name(texture_rate_names(), "rate");
        const SourceLocation step_location = peek().location;
        t.step = texture_count("step number");
        const SourceLocation total_location = peek().location;
        t.total = texture_count("total number of steps");
        if (t.total < 1)
            fail(total_location, "the total number of steps must be at least 1");
        if (t.step > t.total)
            fail(step_location, "step " + std::to_string(t.step) + " is beyond the total of " +
                                    std::to_string(t.total) + " steps");
        while (at(TokenKind::Word)) {
            const Token name = next();
            for (const TextureParameter& p : t.parameters)
                if (p.name == name.text)
                    fail(name.location, "texture parameter '" + name.text +
                                            "' is already given at " + to_string(p.location));
            if (!at(TokenKind::Equals))
                fail_unexpected("'=' after texture parameter '" + name.text + "'");
            next();
            const SignedNumber value =
                expect_number("a number for texture parameter '" + name.text + "'");
            t.parameters.push_back({name.text, value.value, name.location});
        }
        close_paren(open);
        return expr;
    }

    Lexer lexer_;
    std::deque<Token> tokens_;  // read so far; a deque keeps references valid as it grows
    size_t pos_ = 0;
    int depth_ = 0;    // parentheses open at the current token
    int nesting_ = 0;  // parse_expr and parse_unary calls open (see Nesting)
    std::string file_name_;
    const std::set<std::string>& materials_;
    std::vector<std::string> material_list_;
    std::map<std::string, Declaration> declared_;
    std::optional<SourceLocation> render_;
    SourceLocation words_location_;
};

}  // namespace

Script parse_script(std::string_view text, const std::string& file_name,
                    const std::set<std::string>& material_names)
{
    return Parser(text, file_name, material_names).parse();
}

Script parse_script_file(const std::filesystem::path& path,
                         const std::set<std::string>& material_names)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error("cannot open script '" + path.string() + "'");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw std::runtime_error("cannot read script '" + path.string() + "'");
    return parse_script(text.str(), path.string(), material_names);
}

}  // namespace patina::texgen
