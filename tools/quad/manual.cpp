// SPDX-License-Identifier: BSD-3-Clause
#include "manual.hpp"

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace quad::tools {

namespace {

namespace fs = std::filesystem;

/// Text as roff reads it: backslashes and hyphens escaped, no line starting with a control
/// character.
std::string roff(const std::string& text)
{
  std::string out;
  bool line_start = true;
  for (const char c : text) {
    if (line_start && (c == '.' || c == '\'')) {
      out += "\\&";
    }
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else {
      out += c;
    }
    line_start = c == '\n';
  }
  return out;
}

std::vector<CLI::App*> subcommandsOf(CLI::App& app)
{
  return app.get_subcommands([](CLI::App*) { return true; });
}

std::vector<const CLI::Option*> visibleOptions(const CLI::App& app)
{
  return app.get_options([](const CLI::Option* o) { return !o->get_group().empty(); });
}

/// "-n,--count INT": how an option is written.
std::string optionSynopsis(const CLI::Option& o)
{
  std::string names = o.get_name(false, true);
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += names[i] == ',' ? ", " : std::string(1, names[i]);
  }
  const std::string type = o.get_type_name();
  if (o.get_expected_min() > 0 && !type.empty()) {
    out += " " + type;
  }
  return out;
}

struct Page {
  std::vector<std::string> path;  // {"quad", "topic", "list"}
  CLI::App* app;
};

void collect(CLI::App& app, std::vector<std::string> path, std::vector<Page>& pages)
{
  pages.push_back({path, &app});
  for (CLI::App* sub : subcommandsOf(app)) {
    auto next = path;
    next.push_back(sub->get_name());
    collect(*sub, next, pages);
  }
}

std::string join(const std::vector<std::string>& words, const std::string& sep)
{
  std::string out;
  for (const auto& w : words) {
    out += (out.empty() ? "" : sep) + w;
  }
  return out;
}

std::string manPage(const Page& page, std::string_view version)
{
  CLI::App& app = *page.app;
  const std::string name = join(page.path, "-");
  std::string upper = name;
  for (char& c : upper) {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  std::string out = ".TH " + roff(upper) + " 1 \"\" \"" + std::string(version) + "\" \"quad manual\"\n";
  std::string what = app.get_description();
  if (what.starts_with("quad: ")) {
    what.erase(0, 6);  // the main program's description names itself
  }
  out += ".SH NAME\n" + roff(name) + " \\- " + roff(what) + "\n";
  out += ".SH SYNOPSIS\n.B " + roff(join(page.path, " ")) + "\n";
  const auto subs = subcommandsOf(app);
  if (!subs.empty()) {
    out += "\\fICOMMAND\\fR ...\n";
  }
  std::vector<const CLI::Option*> positionals, named;
  for (const CLI::Option* o : visibleOptions(app)) {
    (o->get_name(false, true).front() == '-' ? named : positionals).push_back(o);
  }
  if (!named.empty()) {
    out += "[\\fIOPTIONS\\fR]\n";
  }
  for (const CLI::Option* o : positionals) {
    const std::string word = "\\fI" + roff(o->get_name(true)) + "\\fR" + (o->get_expected_max() > 1 ? " ..." : "");
    out += (o->get_required() ? word : "[" + word + "]") + "\n";
  }
  out += ".SH DESCRIPTION\n" + roff(what) + ".\n";
  if (!app.get_footer().empty()) {
    out += ".PP\n" + roff(app.get_footer()) + "\n";
  }
  if (!positionals.empty()) {
    out += ".SH ARGUMENTS\n";
    for (const CLI::Option* o : positionals) {
      out += ".TP\n.I " + roff(o->get_name(true)) + "\n" + roff(o->get_description()) + "\n";
    }
  }
  if (!named.empty()) {
    out += ".SH OPTIONS\n";
    for (const CLI::Option* o : named) {
      std::string text = o->get_description();
      if (!o->get_default_str().empty()) {
        text += " (default: " + o->get_default_str() + ")";
      }
      out += ".TP\n.B " + roff(optionSynopsis(*o)) + "\n" + roff(text) + "\n";
    }
  }
  if (!subs.empty()) {
    out += ".SH COMMANDS\n";
    for (CLI::App* sub : subs) {
      auto path = page.path;
      path.push_back(sub->get_name());
      out += ".TP\n.B " + roff(sub->get_name()) + "\n" + roff(sub->get_description()) + "; see \\fB" +
             roff(join(path, "-")) + "\\fR(1).\n";
    }
  }
  if (page.path.size() == 1) {
    out += ".SH EXIT STATUS\n0: success. 1: a mission, a check or a run failed. 2: bad input (an unknown "
           "command or option, an invalid manifest, config or value). 3: quad launch: the planner found the "
           "goal cannot be reached, and the vehicle landed.\n";
  }
  out += ".SH SEE ALSO\n";
  std::vector<std::string> see;
  for (std::size_t n = 1; n < page.path.size(); ++n) {
    see.push_back("\\fB" + roff(join({page.path.begin(), page.path.begin() + static_cast<long>(n)}, "-")) + "\\fR(1)");
  }
  out += (see.empty() ? "The documentation in docs/ of quad's sources." : join(see, ", ")) + "\n";
  return out;
}

/// Bash completion: after the words typed so far name a (sub)command, its subcommands and
/// options; files where nothing fits (positional arguments are files or names).
std::string bashCompletion(const std::vector<Page>& pages)
{
  std::string cases;
  std::string children;
  for (const Page& p : pages) {
    std::vector<std::string> words;
    for (CLI::App* sub : subcommandsOf(*p.app)) {
      words.push_back(sub->get_name());
      children += "      \"" + join(p.path, " ") + " " + sub->get_name() + "\") path=\"$path $w\" ;;\n";
    }
    for (const CLI::Option* o : visibleOptions(*p.app)) {
      for (const auto& n : o->get_lnames()) {
        words.push_back("--" + n);
      }
      for (const auto& n : o->get_snames()) {
        words.push_back("-" + n);
      }
    }
    words.push_back("--help");
    cases += "    \"" + join(p.path, " ") + "\") words=\"" + join(words, " ") + "\" ;;\n";
  }
  return "# bash completion for quad, generated from its command-line definitions.\n"
         "_quad() {\n"
         "  local cur=${COMP_WORDS[COMP_CWORD]} path=quad w i words\n"
         "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
         "    w=${COMP_WORDS[i]}\n"
         "    case \"$path $w\" in\n" +
         children +
         "    esac\n"
         "  done\n"
         "  case \"$path\" in\n" +
         cases +
         "  esac\n"
         "  COMPREPLY=($(compgen -W \"$words\" -- \"$cur\"))\n"
         "}\n"
         "complete -o default -F _quad quad\n";
}

void writeFile(const fs::path& file, const std::string& text)
{
  std::ofstream out(file);
  out << text;
  if (!out) {
    throw std::runtime_error("cannot write " + file.string());
  }
}

}  // namespace

int writeManual(CLI::App& app, const fs::path& dir, std::string_view version)
{
  fs::create_directories(dir);
  std::vector<Page> pages;
  collect(app, {"quad"}, pages);
  for (const Page& p : pages) {
    writeFile(dir / (join(p.path, "-") + ".1"), manPage(p, version));
  }
  writeFile(dir / "quad.bash", bashCompletion(pages));
  return static_cast<int>(pages.size());
}

}  // namespace quad::tools
