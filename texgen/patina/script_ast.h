// The syntax tree of a patina script (D&H 1996 §3.2): what parse_script returns and the
// interpreter walks. Plain structs; every statement and expression node carries the
// SourceLocation of its first token so that the interpreter reports errors at the script's
// line and column (throw ScriptError(script.file_name, node.location, ...)).
//
// Units: thicknesses and heights of the layer stack in micrometres, offset radii in metres
// (world units), times in years.
//
// The parser has already checked what can be checked without running the script: material
// names are in the caller's library, texture models and rates are known, step and total are
// whole numbers with 0 <= step <= total, amounts are not negative, curve times ascend, every
// name in an expression is a built-in field or was declared (let, curve, map) before the
// statement that uses it, and every call has the function's number of arguments.
#pragma once

#include "texgen/patina/script_error.h"

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace patina::texgen {

// --- Expressions ---------------------------------------------------------------------------

enum class ExprKind {
    Number,    ///< a literal: `number`
    Name,      ///< a let, curve, map or built-in field: `name`, `name_kind`
    Negate,    ///< -operands[0]
    Add,       ///< operands[0] + operands[1]
    Subtract,  ///< operands[0] - operands[1]
    Multiply,  ///< operands[0] * operands[1]
    Divide,    ///< operands[0] / operands[1]
    Call,      ///< built-in function `name` (script_names.h) of `operands`
    Texture,   ///< a thickness map grown by a model: `texture`
};

/// What a Name refers to.
enum class NameKind {
    Let,    ///< the value of a let statement's expression
    Curve,  ///< a curve statement's curve, evaluated at the current time t
    Map,    ///< a map statement's baked map, read at the surface point
    Field,  ///< a built-in field (script_names.h: t, inclination, height, facing_south)
};

/// texture(MODEL RATE STEP TOTAL [name=value ...]), D&H 1996 §3.3 and §5.1: "the models are
/// identified with the algorithm name, growth rate, step number, and total number of steps".
struct TextureParameter {
    std::string name;
    double value = 0;
    SourceLocation location;  ///< of the parameter's name
};

struct TextureCall {
    std::string model;  ///< one of texture_model_names(): ST RD RDR BD DPD noise turbulence
    std::string rate;   ///< one of texture_rate_names(): linear parabolic logarithmic cubic
    int step = 0;       ///< the step number, 0 <= step <= total
    int total = 1;      ///< the total number of steps, >= 1
    /// Model parameters in the order written, names unique (the interpreter checks that the
    /// model knows them: seed, blocked fraction, patch size, ...).
    std::vector<TextureParameter> parameters;
};

struct Expr {
    ExprKind kind = ExprKind::Number;
    SourceLocation location;     ///< of the first token (the operator for a binary node)
    double number = 0;           ///< Number
    std::string name;            ///< Name: the name; Call: the function
    NameKind name_kind = NameKind::Field;  ///< Name
    std::vector<Expr> operands;  ///< Negate: 1; Add..Divide: left, right; Call: arguments
    TextureCall texture;         ///< Texture
    int depth = 1;               ///< height of this tree (the parser bounds it)
};

/// Deepest expression tree a script may hold, counting parentheses, unary minus signs and
/// operator chains (`1 + 1 + ...`): the parser and the interpreter recurse over the tree.
inline constexpr int kMaxExpressionDepth = 256;

/// The expression fully parenthesised, numbers in shortest form: "(1 + (2 * t))",
/// "clamp(w, 0, 1)", "texture(BD linear 1 20 seed=3)". For messages and tests.
std::string to_string(const Expr& expr);

// --- Statements (one struct per operator, D&H 1996 §3.2) ------------------------------------

/// new MATERIAL: start a stack whose base layer (infinitely thick, §3.1) is MATERIAL.
struct NewStatement {
    SourceLocation location;
    std::string material;
};

/// coat MATERIAL THICKNESS [map]: add a layer of MATERIAL, THICKNESS µm times the map (1
/// where no map is given) thick.
struct CoatStatement {
    SourceLocation location;
    std::string material;
    SourceLocation material_location;
    double thickness_um = 0;
    std::optional<Expr> map;
};

/// erode THICKNESS [map]: remove THICKNESS µm times the map from the top of the stack,
/// through as many layers as it takes.
struct ErodeStatement {
    SourceLocation location;
    double thickness_um = 0;
    std::optional<Expr> map;
};

/// fill MATERIAL HEIGHT [map]: deposit MATERIAL up to HEIGHT µm (times the map) above the
/// base material.
struct FillStatement {
    SourceLocation location;
    std::string material;
    SourceLocation material_location;
    double height_um = 0;
    std::optional<Expr> map;
};

/// polish HEIGHT [map]: remove material above HEIGHT µm (times the map) over the base;
/// polish until FRACTION exposed: remove material from the top down until FRACTION of the
/// area shows the base material.
struct PolishStatement {
    enum class Mode { ToHeight, UntilExposed };
    SourceLocation location;
    Mode mode = Mode::ToHeight;
    double height_um = 0;          ///< ToHeight
    std::optional<Expr> map;       ///< ToHeight
    double exposed_fraction = 0;   ///< UntilExposed, in [0, 1]
};

/// offset MATERIAL RADIUS [tangent | closing]: a thick coat of MATERIAL, less the part a
/// sphere of RADIUS m reaches (Miller 1994's two accessibility variants: the largest tangent
/// sphere, or a positive then negative offset surface). Tangent unless `closing` is given.
struct OffsetStatement {
    enum class Variant { Tangent, Closing };
    SourceLocation location;
    std::string material;
    SourceLocation material_location;
    double radius_m = 0;
    Variant variant = Variant::Tangent;
};

/// render maps: write the stack. At most once, and the last statement of the script.
struct RenderStatement {
    SourceLocation location;
};

/// map NAME = "FILE" ["CHANNEL"]: a baked map (accessibility, exposure, ...) named in
/// expressions. The path is as written; relative paths are for the interpreter to resolve
/// (against the script's folder). An empty channel means the file's first channel.
/// map NAME = material "SOURCE": the mesh's source material SOURCE as a mask, 1 on its
/// texels and 0 elsewhere (`path` empty).
struct MapStatement {
    SourceLocation location;
    std::string name;
    std::string path;
    std::string channel;
    std::string material;
};

/// curve NAME = (t0 v0, t1 v1, ...): a piecewise-linear function of time (years), times
/// strictly ascending; constant before the first and after the last point.
struct CurvePoint {
    double time_years = 0;
    double value = 0;
};

struct CurveStatement {
    SourceLocation location;
    std::string name;
    std::vector<CurvePoint> points;  ///< at least one
};

/// let NAME = expr: a named expression, evaluated where it is used.
struct LetStatement {
    SourceLocation location;
    std::string name;
    Expr value;
};

using Statement = std::variant<NewStatement, CoatStatement, ErodeStatement, FillStatement,
                               PolishStatement, OffsetStatement, RenderStatement, MapStatement,
                               CurveStatement, LetStatement>;

/// The location of a statement's keyword.
SourceLocation location_of(const Statement& statement);
/// The keyword of a statement: "coat", "erode", ...
std::string keyword_of(const Statement& statement);

struct Script {
    std::string file_name;  ///< as given to the parser, for messages
    std::vector<Statement> statements;  ///< in the order written
};

}  // namespace patina::texgen
