// SPDX-License-Identifier: BSD-3-Clause
#include "quad/introspection/idl.hpp"

#include <cctype>
#include <charconv>
#include <functional>
#include <set>

namespace quad::introspection {

std::size_t cdrSize(Primitive p)
{
  switch (p) {
    case Primitive::kBool:
    case Primitive::kOctet:
    case Primitive::kChar:
      return 1;
    case Primitive::kInt16:
    case Primitive::kUInt16:
      return 2;
    case Primitive::kInt32:
    case Primitive::kUInt32:
    case Primitive::kFloat:
      return 4;
    case Primitive::kInt64:
    case Primitive::kUInt64:
    case Primitive::kDouble:
      return 8;
  }
  return 1;
}

namespace {

struct Token {
  std::string text;
  int line = 0;
  std::size_t offset = 0;  // in the file's text
};

std::vector<Token> tokenize(std::string_view text, std::string_view file)
{
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  const auto fail = [&](const std::string& why) {
    throw IdlError(std::string(file) + ":" + std::to_string(line) + ": " + why);
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c)) != 0) {
      ++i;
    } else if (text.substr(i, 2) == "//" || c == '#') {
      // Comments and preprocessor lines (#include: every file is parsed on its own).
      while (i < text.size() && text[i] != '\n') {
        ++i;
      }
    } else if (text.substr(i, 2) == "/*") {
      const auto end = text.find("*/", i + 2);
      if (end == std::string_view::npos) {
        fail("unterminated comment");
      }
      for (std::size_t k = i; k < end; ++k) {
        line += text[k] == '\n' ? 1 : 0;
      }
      i = end + 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_') {
      // A word, or a number (a decimal point in a literal: @default(1.0)).
      const std::size_t start = i;
      const bool number = std::isdigit(static_cast<unsigned char>(c)) != 0;
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) != 0 || text[i] == '_' ||
                                 (number && text[i] == '.'))) {
        ++i;
      }
      tokens.push_back({std::string(text.substr(start, i - start)), line, start});
    } else if (text.substr(i, 2) == "::") {
      tokens.push_back({"::", line, i});
      i += 2;
    } else if (std::string_view("{};<>,[]()@=").find(c) != std::string_view::npos) {
      tokens.push_back({std::string(1, c), line, i});
      ++i;
    } else if (c == '"') {
      const auto end = text.find('"', i + 1);
      if (end == std::string_view::npos) {
        fail("unterminated string literal");
      }
      tokens.push_back({std::string(text.substr(i, end + 1 - i)), line, i});
      i = end + 1;
    } else {
      fail(std::string("unexpected character '") + c + "'");
    }
  }
  return tokens;
}

}  // namespace

/// Recursive-descent parser over the tokens of one file.
class Parser {
public:
  Parser(Schema& schema, std::string_view file, std::string_view text)
      : schema_(schema), file_(file), text_(text), tokens_(tokenize(text, file))
  {
  }

  void parseFile()
  {
    while (!atEnd()) {
      parseDefinition();
    }
  }

private:
  bool atEnd() const { return pos_ >= tokens_.size(); }
  const Token& peek() const
  {
    static const Token kEnd{"<end of file>", 0, 0};
    return atEnd() ? kEnd : tokens_[pos_];
  }
  [[noreturn]] void fail(const std::string& why) const
  {
    const int line = atEnd() ? (tokens_.empty() ? 1 : tokens_.back().line) : peek().line;
    throw IdlError(file_ + ":" + std::to_string(line) + ": " + why + " (at '" + peek().text + "')");
  }
  std::string next()
  {
    if (atEnd()) {
      fail("unexpected end of file");
    }
    return tokens_[pos_++].text;
  }
  void expect(std::string_view text)
  {
    if (peek().text != text) {
      fail("expected '" + std::string(text) + "'");
    }
    ++pos_;
  }
  bool accept(std::string_view text)
  {
    if (!atEnd() && peek().text == text) {
      ++pos_;
      return true;
    }
    return false;
  }
  std::string identifier()
  {
    const std::string id = next();
    if (id.empty() || (std::isalpha(static_cast<unsigned char>(id[0])) == 0 && id[0] != '_')) {
      --pos_;
      fail("expected an identifier");
    }
    return id;
  }
  std::uint32_t number()
  {
    const std::string text = next();
    std::uint32_t value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || ptr != text.data() + text.size()) {
      --pos_;
      fail("expected a positive integer");
    }
    return value;
  }
  std::string scoped(const std::string& name) const
  {
    std::string out;
    for (const auto& m : scope_) {
      out += m + "::";
    }
    return out + name;
  }
  std::string scopeText() const
  {
    std::string out;
    for (const auto& m : scope_) {
      out += (out.empty() ? "" : "::") + m;
    }
    return out;
  }

  std::vector<std::string> annotations()
  {
    std::vector<std::string> out;
    while (accept("@")) {
      out.push_back(identifier());
      if (accept("(")) {
        int depth = 1;
        while (depth > 0) {
          const std::string t = next();
          depth += t == "(" ? 1 : (t == ")" ? -1 : 0);
        }
      }
    }
    return out;
  }

  void parseDefinition()
  {
    annotations();
    const std::size_t start = peek().offset;
    const std::string keyword = next();
    if (keyword == "module") {
      scope_.push_back(identifier());
      expect("{");
      while (!accept("}")) {
        parseDefinition();
      }
      expect(";");
      scope_.pop_back();
    } else if (keyword == "struct") {
      parseStruct(start);
    } else if (keyword == "enum") {
      parseEnum(start);
    } else {
      --pos_;
      fail("expected module, struct or enum");
    }
  }

  void record(const std::string& name, std::size_t start)
  {
    const std::size_t end = tokens_[pos_ - 1].offset + 1;
    schema_.definition_text_[name] = std::string(text_.substr(start, end - start));
  }

  void parseStruct(std::size_t start)
  {
    StructDef def;
    def.name = scoped(identifier());
    def.file = file_;
    expect("{");
    while (!accept("}")) {
      Member member;
      member.annotations = annotations();
      member.type = parseType();
      member.name = identifier();
      while (accept("[")) {
        member.array_dims.push_back(number());
        expect("]");
      }
      expect(";");
      def.members.push_back(std::move(member));
    }
    expect(";");
    if (def.members.empty()) {
      fail("struct " + def.name + " has no members");
    }
    record(def.name, start);
    const std::string name = def.name;
    if (!schema_.structs_.emplace(name, std::move(def)).second) {
      fail("struct " + name + " defined twice");
    }
  }

  void parseEnum(std::size_t start)
  {
    EnumDef def;
    def.name = scoped(identifier());
    def.file = file_;
    expect("{");
    do {
      annotations();
      def.enumerators.push_back(identifier());
    } while (accept(","));
    expect("}");
    expect(";");
    record(def.name, start);
    const std::string name = def.name;
    if (!schema_.enums_.emplace(name, std::move(def)).second) {
      fail("enum " + name + " defined twice");
    }
  }

  TypeRef parseType()
  {
    TypeRef t;
    const std::string first = next();
    const auto primitive = [&t](Primitive p) {
      t.kind = TypeRef::Kind::kPrimitive;
      t.primitive = p;
      return t;
    };
    if (first == "boolean") return primitive(Primitive::kBool);
    if (first == "octet" || first == "uint8") return primitive(Primitive::kOctet);
    if (first == "char" || first == "int8") return primitive(Primitive::kChar);
    if (first == "short" || first == "int16") return primitive(Primitive::kInt16);
    if (first == "float") return primitive(Primitive::kFloat);
    if (first == "double") return primitive(Primitive::kDouble);
    if (first == "int32") return primitive(Primitive::kInt32);
    if (first == "uint32") return primitive(Primitive::kUInt32);
    if (first == "int64") return primitive(Primitive::kInt64);
    if (first == "uint64") return primitive(Primitive::kUInt64);
    if (first == "uint16") return primitive(Primitive::kUInt16);
    if (first == "long") {
      return primitive(accept("long") ? Primitive::kInt64 : Primitive::kInt32);
    }
    if (first == "unsigned") {
      const std::string second = next();
      if (second == "short") return primitive(Primitive::kUInt16);
      if (second == "long") {
        return primitive(accept("long") ? Primitive::kUInt64 : Primitive::kUInt32);
      }
      --pos_;
      fail("expected short or long after unsigned");
    }
    if (first == "string") {
      t.kind = TypeRef::Kind::kString;
      if (accept("<")) {
        t.bound = number();
        expect(">");
      }
      return t;
    }
    if (first == "sequence") {
      t.kind = TypeRef::Kind::kSequence;
      expect("<");
      t.element = std::make_shared<TypeRef>(parseType());
      if (accept(",")) {
        t.bound = number();
      }
      expect(">");
      return t;
    }
    // A scoped name: Header, quad::msg::Header, ::quad::msg::Header.
    --pos_;
    std::string name;
    if (accept("::")) {
      name = "::";
    }
    name += identifier();
    while (accept("::")) {
      name += "::" + identifier();
    }
    t.kind = TypeRef::Kind::kNamed;
    t.name = name;
    t.scope = scopeText();
    return t;
  }

  Schema& schema_;
  std::string file_;
  std::string_view text_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::vector<std::string> scope_;
};

void Schema::addFile(std::string_view file_name, std::string_view text)
{
  const auto [it, inserted] = file_text_.emplace(std::string(file_name), std::string(text));
  if (!inserted) {
    throw IdlError(std::string(file_name) + ": added twice");
  }
  Parser(*this, file_name, it->second).parseFile();
}

const StructDef* Schema::findStruct(std::string_view scoped_name) const
{
  const auto it = structs_.find(scoped_name);
  return it == structs_.end() ? nullptr : &it->second;
}

const EnumDef* Schema::findEnum(std::string_view scoped_name) const
{
  const auto it = enums_.find(scoped_name);
  return it == enums_.end() ? nullptr : &it->second;
}

std::string Schema::enumeratorName(std::string_view enum_name, std::int64_t value) const
{
  const EnumDef* e = findEnum(enum_name);
  if (e == nullptr || value < 0 || static_cast<std::uint64_t>(value) >= e->enumerators.size()) {
    return std::string(enum_name) + " " + std::to_string(value);
  }
  return e->enumerators[static_cast<std::size_t>(value)];
}

std::optional<std::string> Schema::resolve(std::string_view name, std::string_view scope) const
{
  const auto known = [this](const std::string& n) {
    return structs_.contains(n) || enums_.contains(n);
  };
  if (name.starts_with("::")) {
    std::string n(name.substr(2));
    return known(n) ? std::optional(n) : std::nullopt;
  }
  std::string s(scope);
  while (true) {
    const std::string candidate = s.empty() ? std::string(name) : s + "::" + std::string(name);
    if (known(candidate)) {
      return candidate;
    }
    if (s.empty()) {
      return std::nullopt;
    }
    const auto cut = s.rfind("::");
    s = cut == std::string::npos ? "" : s.substr(0, cut);
  }
}

namespace {
/// Calls `f` on every named type in `t` (itself, or a sequence's element, recursively).
template <class Type, class F>
void forEachNamed(Type& t, F&& f)
{
  if (t.kind == TypeRef::Kind::kNamed) {
    f(t);
  } else if (t.kind == TypeRef::Kind::kSequence) {
    forEachNamed(*t.element, f);
  }
}
}  // namespace

void Schema::link()
{
  for (auto& entry : structs_) {
    const std::string& name = entry.first;
    StructDef& def = entry.second;
    for (auto& m : def.members) {
      forEachNamed(m.type, [&](TypeRef& t) {
        auto resolved = resolve(t.name, t.scope);
        if (!resolved) {
          throw IdlError(def.file + ": " + name + "." + m.name + ": unknown type '" + t.name + "'");
        }
        t.name = *resolved;
        t.scope.clear();
      });
    }
  }
}

std::string Schema::flattenedIdl(std::string_view type_name) const
{
  std::vector<std::string> order;
  std::set<std::string, std::less<>> seen;
  std::function<void(const std::string&)> visit = [&](const std::string& name) {
    if (seen.contains(name)) {
      return;
    }
    seen.insert(name);
    if (const StructDef* s = findStruct(name)) {
      for (const auto& m : s->members) {
        forEachNamed(m.type, [&](const TypeRef& t) { visit(t.name); });
      }
    } else if (!findEnum(name)) {
      throw IdlError("no IDL type named '" + name + "'");
    }
    order.push_back(name);
  };
  visit(std::string(type_name));

  std::string out;
  for (const auto& name : order) {
    // Re-open the definition's modules around its original text.
    std::vector<std::string> modules;
    std::string_view rest = name;
    for (auto cut = rest.find("::"); cut != std::string_view::npos; cut = rest.find("::")) {
      modules.emplace_back(rest.substr(0, cut));
      rest = rest.substr(cut + 2);
    }
    for (const auto& m : modules) {
      out += "module " + m + " {\n";
    }
    out += definition_text_.find(name)->second + "\n";
    for (std::size_t i = 0; i < modules.size(); ++i) {
      out += "};\n";
    }
  }
  return out;
}

}  // namespace quad::introspection
