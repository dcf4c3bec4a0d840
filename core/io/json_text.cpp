#include "core/io/json_text.hpp"

#include <iterator>
#include <set>
#include <stdexcept>
#include <vector>

namespace drape {

namespace {

// Input nlohmann would accept but a reader must not: `path` is where in the value it was found.
struct RefusedJson : std::runtime_error {
  RefusedJson(std::string where, const std::string& message)
      : std::runtime_error(message), path(std::move(where)) {}
  std::string path;
};

// Checks the text while nlohmann parses it, through the parser callback, which sees every
// bracket before the parser recurses further (so throwing there stops it in time) and every
// key: the nesting depth, and keys repeated in one object, of which nlohmann would silently keep
// the last value (a scene with "dt" twice would run with whichever came last).
class ParseGuard {
 public:
  bool operator()(int, nlohmann::json::parse_event_t e, const nlohmann::json& parsed) {
    using event = nlohmann::json::parse_event_t;
    if (e == event::object_start || e == event::array_start) {
      if (m_open.size() >= static_cast<std::size_t>(max_json_depth))
        throw RefusedJson("", "nested deeper than " + std::to_string(max_json_depth) + " levels");
      m_open.push_back({e == event::object_start, child_label(), {}, "", 0});
    } else if (e == event::key) {
      Level& level = m_open.back();
      level.key = parsed.get<std::string>();
      if (!level.keys.insert(level.key).second)
        throw RefusedJson(path(), "the key is repeated in its object (only one value can be kept)");
    } else if (e == event::object_end || e == event::array_end) {
      m_open.pop_back();
      count_item();
    } else if (e == event::value) {
      count_item();
    }
    return true;
  }

 private:
  struct Level {
    bool object;
    std::string label;  // ".key" or "[index]" in its parent, "" at the root
    std::set<std::string> keys;
    std::string key;  // the key whose value is being read
    std::size_t items;  // the values an array has read
  };

  std::string child_label() const {
    if (m_open.empty()) return "";
    const Level& parent = m_open.back();
    return parent.object ? "." + parent.key : "[" + std::to_string(parent.items) + "]";
  }
  void count_item() {
    if (!m_open.empty() && !m_open.back().object) ++m_open.back().items;
  }
  // The dotted path of the key being read, e.g. "input.events[2].t".
  std::string path() const {
    std::string out;
    for (const Level& level : m_open) out += level.label;
    out += "." + m_open.back().key;
    return out.front() == '.' ? out.substr(1) : out;  // a root array starts "[0]"
  }

  std::vector<Level> m_open;
};

// The error for a value the guard refused, at its `path` inside the value found at `field`.
InputError refused(const RefusedJson& e, const std::string& file, const std::string& field) {
  const std::string path = field.empty() ? e.path : e.path.empty() ? field : field + "." + e.path;
  return InputError(file, path, std::string("not accepted JSON: ") + e.what());
}

template <class Source>
nlohmann::json parse_bounded(Source&& source, const std::string& file, const std::string& field) {
  try {
    return nlohmann::json::parse(std::forward<Source>(source), ParseGuard());
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range
    throw InputError(file, field, "not valid JSON: " + shorten(e.what()));
  } catch (const RefusedJson& e) {
    throw refused(e, file, field);
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

// nlohmann's lexer takes a NUL byte for the end of the input (for C strings), so whatever
// follows one would be dropped without a word: JSON text has no NUL, so it is refused.
void check_no_nul(const std::string& text, const std::string& file, const std::string& field) {
  const auto at = text.find('\0');
  if (at != std::string::npos)
    throw InputError(file, field, "not valid JSON: a NUL byte at offset " + std::to_string(at));
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const std::string& field) {
  check_no_nul(text, file, field);
  return parse_bounded(text, file, field);
}

std::optional<nlohmann::json> try_parse_json_text(const std::string& text, const std::string& file,
                                                  const std::string& field) {
  if (text.find('\0') != std::string::npos) return std::nullopt;  // not valid JSON
  try {
    return nlohmann::json::parse(text, ParseGuard());
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  } catch (const RefusedJson& e) {
    throw refused(e, file, field);
  }
}

nlohmann::json parse_json_stream(std::istream& in, const std::string& file) {
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return parse_json_text(text, file);
}

std::string quote_json(const nlohmann::json& value) {
  std::string out;
  constexpr int levels = 4;  // enough for [row, col] lists and small objects
  append_brief(value, levels, out);
  return shorten(out, max_quoted_chars);
}

std::string quote_text(std::string_view text) {
  if (text.size() <= max_quoted_chars) return "\"" + std::string(text) + "\"";
  std::size_t cut = max_quoted_chars - 3;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return "\"" + std::string(text.substr(0, cut)) + "...\"";
}

bool is_utf8(const std::string& text) {
  try {
    static_cast<void>(nlohmann::json(text).dump());
    return true;
  } catch (const nlohmann::json::type_error&) {  // 316: invalid UTF-8 byte
    return false;
  }
}

}  // namespace drape
