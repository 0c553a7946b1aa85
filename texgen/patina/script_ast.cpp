#include "texgen/patina/script_ast.h"

#include "texgen/patina/script_names.h"

#include <charconv>

namespace patina::texgen {

namespace {

std::string number_text(double value)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

// Appending rather than "(" + std::string&& (which GCC 12 warns about, -Wrestrict, a known
// false positive).
std::string binary(const Expr& expr, const char* op)
{
    std::string text = "(";
    text += to_string(expr.operands.at(0));
    text += " ";
    text += op;
    text += " ";
    text += to_string(expr.operands.at(1));
    return text += ")";
}

}  // namespace

std::string to_string(const Expr& expr)
{
    switch (expr.kind) {
    case ExprKind::Number: return number_text(expr.number);
    case ExprKind::Name: return expr.name;
    case ExprKind::Negate: {
        std::string text = "(-";
        text += to_string(expr.operands.at(0));
        return text += ")";
    }
    case ExprKind::Add: return binary(expr, "+");
    case ExprKind::Subtract: return binary(expr, "-");
    case ExprKind::Multiply: return binary(expr, "*");
    case ExprKind::Divide: return binary(expr, "/");
    case ExprKind::Call: {
        std::string text = expr.name + "(";
        for (size_t i = 0; i < expr.operands.size(); ++i)
            text += (i > 0 ? ", " : "") + to_string(expr.operands[i]);
        return text + ")";
    }
    case ExprKind::Texture: {
        const TextureCall& t = expr.texture;
        std::string text = "texture(" + t.model + " " + t.rate + " " + std::to_string(t.step) +
                           " " + std::to_string(t.total);
        for (const TextureParameter& p : t.parameters)
            text += " " + p.name + "=" + number_text(p.value);
        return text + ")";
    }
    }
    return "?";
}

SourceLocation location_of(const Statement& statement)
{
    return std::visit([](const auto& s) { return s.location; }, statement);
}

std::string keyword_of(const Statement& statement)
{
    // operator_keywords() lists the keywords in the order of the variant's alternatives.
    static_assert(std::variant_size_v<Statement> == 10);
    return operator_keywords()[statement.index()];
}

}  // namespace patina::texgen
