#include "smart/record/schemas.hpp"

#include <cctype>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace smart::record {

namespace {

struct Field {
  std::string type;    // .msg type: "float64", "geometry_msgs/Pose"
  std::string suffix;  // "", "[]" or "[36]"
  std::string name;
  bool nested = false;  // a message type (listed after the root)
};
using Messages = std::map<std::string, std::vector<Field>>;  // "pkg/Type" -> fields

std::vector<std::string> tokens(std::string_view text) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (text.substr(i, 2) == "//") {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (text.substr(i, 2) == "::") {
      out.emplace_back("::");
      i += 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i;
      while (j < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
        ++j;
      out.emplace_back(text.substr(i, j - i));
      i = j;
    } else {
      out.emplace_back(1, c);
      ++i;
    }
  }
  return out;
}

const std::map<std::string, std::string, std::less<>>& primitives() {
  static const std::map<std::string, std::string, std::less<>> m = {
      {"boolean", "bool"},
      {"octet", "byte"},
      {"char", "char"},
      {"int8", "int8"},
      {"uint8", "uint8"},
      {"short", "int16"},
      {"unsigned short", "uint16"},
      {"long", "int32"},
      {"unsigned long", "uint32"},
      {"long long", "int64"},
      {"unsigned long long", "uint64"},
      {"float", "float32"},
      {"double", "float64"},
      {"string", "string"}};
  return m;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : t_(tokens(text)) {}
  Messages parse() {
    while (i_ < t_.size()) statement();
    return std::move(messages_);
  }

 private:
  const std::string& next() {
    if (i_ >= t_.size()) throw std::invalid_argument("IDL: unexpected end of text");
    return t_[i_++];
  }
  const std::string& peek() const {
    static const std::string e;
    return i_ < t_.size() ? t_[i_] : e;
  }
  void expect(std::string_view s) {
    if (next() != s) {
      throw std::invalid_argument("IDL: expected '" + std::string(s) + "' before token " +
                                  std::to_string(i_));
    }
  }
  void statement() {
    const std::string tok = next();
    if (tok == "@") {
      next();  // the annotation's name
    } else if (tok == "module") {
      modules_.push_back(next());
      expect("{");
    } else if (tok == "}") {
      if (!modules_.empty()) modules_.pop_back();
      if (peek() == ";") next();
    } else if (tok == "struct") {
      structure();
    }
  }
  // pkg::msg::dds_::Name_ (or Name_ inside pkg's module) -> pkg/Name.
  std::string msg_name(const std::vector<std::string>& scoped) const {
    std::string name = scoped.back();
    if (!name.empty() && name.back() == '_') name.pop_back();
    const std::string pkg = scoped.size() > 1 ? scoped.front() : modules_.front();
    return pkg + "/" + name;
  }
  Field type() {
    if (peek() == "sequence") {
      next();
      expect("<");
      Field f = type();
      expect(">");
      f.suffix = "[]";
      return f;
    }
    std::string word = next();
    // unsigned short, unsigned long, long long, unsigned long long
    auto last = [&] { return word.substr(word.rfind(' ') + 1); };
    while ((last() == "unsigned" || last() == "long") && (peek() == "long" || peek() == "short")) {
      word += " " + next();
    }
    if (const auto p = primitives().find(word); p != primitives().end())
      return {p->second, "", "", false};
    std::vector<std::string> scoped{word};
    while (peek() == "::") {
      next();
      scoped.push_back(next());
    }
    return {msg_name(scoped), "", "", true};
  }
  void structure() {
    const std::string name = msg_name({next()});
    expect("{");
    std::vector<Field> fields;
    while (peek() != "}") {
      Field f = type();
      f.name = next();
      if (peek() == "[") {
        next();
        f.suffix = "[" + next() + "]";
        expect("]");
      }
      expect(";");
      fields.push_back(std::move(f));
    }
    next();
    expect(";");
    messages_[name] = std::move(fields);
  }

  std::vector<std::string> t_;
  std::size_t i_ = 0;
  std::vector<std::string> modules_;
  Messages messages_;
};

const std::vector<Field>& fields_of(const Messages& m, const std::string& type) {
  const auto it = m.find(type);
  if (it == m.end()) {
    throw std::invalid_argument("ros2msg schema: message " + type +
                                " is not defined in the IDL; add it to idl/ros2.idl");
  }
  return it->second;
}

void append_body(std::string& out, const std::vector<Field>& fields) {
  for (const auto& f : fields) out += f.type + f.suffix + " " + f.name + "\n";
}

void dependencies(const Messages& m, const std::string& type, std::vector<std::string>& order,
                  std::set<std::string>& seen) {
  for (const auto& f : fields_of(m, type)) {
    if (f.nested && seen.insert(f.type).second) {
      order.push_back(f.type);
      dependencies(m, f.type, order, seen);
    }
  }
}

}  // namespace

std::string ros2msg_definition(std::string_view idl_text, std::string_view ros_type) {
  // "pkg/msg/Type" -> "pkg/Type"
  std::string type(ros_type);
  if (const auto p = type.find("/msg/"); p != std::string::npos) type.erase(p, 4);
  const Messages m = Parser(idl_text).parse();
  std::string out;
  append_body(out, fields_of(m, type));
  std::vector<std::string> order;
  std::set<std::string> seen{type};
  dependencies(m, type, order, seen);
  for (const auto& dep : order) {
    out += std::string(80, '=') + "\nMSG: " + dep + "\n";
    append_body(out, fields_of(m, dep));
  }
  return out;
}

std::string ros2msg_definition(std::string_view ros_type) {
  return ros2msg_definition(ros2_idl_text(), ros_type);
}

}  // namespace smart::record
