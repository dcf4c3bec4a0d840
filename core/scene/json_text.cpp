#include "core/scene/json_text.hpp"

namespace drape {

namespace {

// Tracks the depth through nlohmann's parser callback; the callback sees every opening and
// closing bracket before the parser recurses further, so throwing there stops it in time.
nlohmann::json::parser_callback_t depth_guard(int& depth) {
  using event = nlohmann::json::parse_event_t;
  return [&depth](int, event e, nlohmann::json&) {
    if (e == event::object_start || e == event::array_start) {
      if (++depth > max_json_depth)
        throw std::length_error("nested deeper than " + std::to_string(max_json_depth) +
                                " levels");
    } else if (e == event::object_end || e == event::array_end) {
      --depth;
    }
    return true;
  };
}

template <class Source>
nlohmann::json parse_bounded(Source&& source, const std::string& file, const std::string& field) {
  int depth = 0;
  try {
    return nlohmann::json::parse(std::forward<Source>(source), depth_guard(depth));
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range
    throw InputError(file, field, "not valid JSON: " + shorten(e.what()));
  } catch (const std::length_error& e) {
    throw InputError(file, field, std::string("not accepted JSON: ") + e.what());
  }
}

// Appends `value` to `out`, stopping once `out` is longer than the budget.
void append_brief(const nlohmann::json& value, int levels, std::string& out) {
  if (out.size() > max_quoted_chars) return;
  if (!value.is_structured()) {
    std::string text = value.dump();
    if (text.size() > max_quoted_chars) text.resize(max_quoted_chars + 1);  // cut with "..."
    out += text;
    return;
  }
  const bool object = value.is_object();
  out += object ? "{" : "[";
  if (levels == 0 && !value.empty()) {
    out += "...";
  } else {
    bool first = true;
    for (auto it = value.begin(); it != value.end() && out.size() <= max_quoted_chars; ++it) {
      if (!first) out += ", ";
      first = false;
      if (object) out += nlohmann::json(it.key()).dump() + ": ";
      append_brief(*it, levels - 1, out);
    }
  }
  out += object ? "}" : "]";
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const std::string& field) {
  return parse_bounded(text, file, field);
}

std::optional<nlohmann::json> try_parse_json_text(const std::string& text, const std::string& file,
                                                  const std::string& field) {
  int depth = 0;
  try {
    return nlohmann::json::parse(text, depth_guard(depth));
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  } catch (const std::length_error& e) {
    throw InputError(file, field, std::string("not accepted JSON: ") + e.what());
  }
}

nlohmann::json parse_json_stream(std::istream& in, const std::string& file) {
  return parse_bounded(in, file, "");
}

std::string quote_json(const nlohmann::json& value) {
  std::string out;
  constexpr int levels = 4;  // enough for [row, col] lists and small objects
  append_brief(value, levels, out);
  return shorten(out, max_quoted_chars);
}

}  // namespace drape
