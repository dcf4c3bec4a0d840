#pragma once
// JSON text in and out with bounds (docs/scene.md, Limits): parsing refuses nesting deeper than
// max_json_depth, so no input can exhaust the stack of nlohmann's recursive parser, printer or
// destructor, and a key repeated in one object, which nlohmann would silently resolve to its last
// value; messages quote values shortened, so a huge wrong-typed value is not printed whole.
#include <cstddef>
#include <istream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/io/input_error.hpp"

namespace drape {

/// The deepest nesting of arrays and objects any input may have.
constexpr int max_json_depth = 64;
/// The longest quoted value in a message, in characters, "..." included.
constexpr std::size_t max_quoted_chars = 200;

/// Parses JSON text; throws InputError(file, field, ...) when it is not valid JSON, nests
/// deeper than max_json_depth or repeats a key (the error then names the key's path in `field`).
nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const std::string& field = "");
/// Parses `text` when it is valid JSON (nothing when it is not); throws InputError(file, field)
/// only when it nests deeper than max_json_depth or repeats a key.
std::optional<nlohmann::json> try_parse_json_text(const std::string& text, const std::string& file,
                                                  const std::string& field);
/// The same for a stream (a whole file).
nlohmann::json parse_json_stream(std::istream& in, const std::string& file);
/// `value` printed for a message: nesting below a few levels as "...", at most
/// max_quoted_chars characters.
std::string quote_json(const nlohmann::json& value);
/// Raw text (a field of a CSV line, a token) in double quotes for a message, cut after
/// max_quoted_chars characters with "..." (at a UTF-8 character's start): a line without
/// separators is one field, and quoting it whole made a megabyte message.
std::string quote_text(std::string_view text);
/// Whether `text` is valid UTF-8, as a JSON string must be: a file's strings are (the parser
/// checks them), but a command line's bytes or a path need not be.
bool is_utf8(const std::string& text);

}  // namespace drape
