// The parser of the patina script language: the "simple scripting language to describe the
// sequential application of different operators" of Dorsey & Hanrahan 1996 §3.2, in which
// the copper strips of §5.1 are written. It reads the paper's three scripts exactly as
// printed, and extends them with maps, curves, named expressions and arithmetic for the
// environment-driven scripts of §5.2-5.3.
//
// Grammar (EBNF; `{ }` repeats, `[ ]` is optional, "..." is a literal word or character):
//
//   script     = { statement | ";" | NEWLINE } ;
//   statement  = ( new | coat | erode | fill | polish | offset | render | map | curve | let )
//                ( ";" | NEWLINE | END ) ;
//   new        = "new" MATERIAL ;
//   coat       = "coat" MATERIAL THICKNESS [ expr ] ;         (* µm, times the map expr *)
//   erode      = "erode" THICKNESS [ expr ] ;                 (* µm *)
//   fill       = "fill" MATERIAL HEIGHT [ expr ] ;            (* µm above the base *)
//   polish     = "polish" HEIGHT [ expr ]
//              | "polish" "until" FRACTION "exposed" ;        (* fraction of area, 0..1 *)
//   offset     = "offset" MATERIAL RADIUS [ "tangent" | "closing" ] ;   (* m; tangent *)
//   render     = "render" "maps" ;                            (* once, last *)
//   map        = "map" NAME "=" STRING [ STRING ] ;           (* file, channel *)
//   curve      = "curve" NAME "=" "(" POINT { "," POINT } ")" ;
//   POINT      = NUMBER NUMBER ;                              (* time (years), value *)
//   let        = "let" NAME "=" expr ;
//
//   expr       = term { ( "+" | "-" ) term } ;
//   term       = unary { ( "*" | "/" ) unary } ;
//   unary      = "-" unary | primary ;
//   primary    = NUMBER | NAME | "(" expr ")" | texture
//              | FUNCTION "(" [ expr { "," expr } ] ")" ;
//   texture    = "texture" "(" MODEL RATE STEP TOTAL { WORD "=" NUMBER } ")" ;
//
//   MATERIAL   = WORD { WORD } [ INTEGER ] ;   (* a name in the material library *)
//   THICKNESS, HEIGHT, RADIUS = number ;        (* "-" before one is an error *)
//   FRACTION   = number ;                       (* 0 <= FRACTION <= 1 *)
//   STEP, TOTAL = INTEGER ;                     (* digits only *)
//   NUMBER     = [ "-" ] number ;               (* 3, 0.35, .5, 1e-3 *)
//
// A statement ends at ";" or at the end of its line, except inside parentheses: a long
// expression or curve continues over lines when it is in parentheses. "#" and "//" start a
// comment that runs to the end of the line.
//
// Material names. The material is the words up to the first number. If two numbers follow
// and the first is written as a whole number ("3", not "3.0"), the first is the stage
// number of the material and part of its name, the second is the amount:
// `coat marine patina 3 3.0 texture(BD linear 10 20)` coats "marine patina 3" 3.0 µm thick,
// `coat dirt 1.9 texture(BD linear 5 20)` coats "dirt" 1.9 µm thick (D&H 1996 §5.1: "the
// integer indicates the specific stage"). When the library does not know the name with the
// stage but knows it without, the plain reading is taken (`coat dirt 2 0.5 * w` is "dirt",
// 2 µm, times 0.5 * w). A name the library does not know is an error with a suggestion.
//
// Names. A NAME in an expression is a built-in field (script_names.h: t, inclination,
// height, facing_south) or a let, curve or map declared on an earlier line; names are
// declared once and may not be keywords, fields or functions. A curve named in an
// expression is its value at the current time t. FUNCTION is one of script_names.h's
// functions (clamp, min, max, smoothstep, mix, pow, abs, step). MODEL is ST, RD, RDR, BD,
// DPD, noise or turbulence, RATE linear, parabolic, logarithmic or cubic (§3.3), STEP and
// TOTAL whole numbers with 0 <= STEP <= TOTAL and TOTAL >= 1 (§5.1: "the models are
// identified with the algorithm name, growth rate, step number, and total number of
// steps").
//
// Errors are ScriptError, "FILE:LINE:COL: error: ..." naming the offending token.
#pragma once

#include "texgen/patina/script_ast.h"

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

namespace patina::texgen {

/// Parse a script. `file_name` names it in messages; `material_names` is the material
/// library ("copper", "tarnish 1", "marine patina 3", ...) that material names resolve
/// against. Throws ScriptError at the first error.
Script parse_script(std::string_view text, const std::string& file_name,
                    const std::set<std::string>& material_names);

/// Read and parse a script file. Throws std::runtime_error naming the path if it cannot be
/// read, ScriptError for an error in it.
Script parse_script_file(const std::filesystem::path& path,
                         const std::set<std::string>& material_names);

}  // namespace patina::texgen
