// Strict readers of option values: no value ignored, no hexadecimal or overflowing number, every range checked.
#include "signorini/core/options.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/core/option_paths.hpp"
#include "signorini/core/parse.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <system_error>

#include <yaml.h>

namespace signorini {

namespace {

constexpr const char *REAL_GRAMMAR = "a finite real number in decimal or scientific notation";

std::string Interval(double lo, double hi, bool lo_open, bool hi_open) {
  return std::string(lo_open ? "(" : "[") + FormatNumber(lo) + ", " + FormatNumber(hi) + (hi_open ? ")" : "]");
}

/// The raw text of option name ("" when it is given without a value); found = whether it is given at all. The PETSc
/// reader call before it has listed the option for -help and marked it used.
PetscErrorCode RawValue(PetscOptionItems *PetscOptionsObject, const char *name, std::string &raw, PetscBool &found) {
  const char *value = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(PetscOptionsObject->options, PetscOptionsObject->prefix, name, &value, &found));
  raw = found && value ? value : "";
  PetscFunctionReturn(0);
}

/// Lists option name in -help (with its default and help text), then returns its raw text.
PetscErrorCode ListAndRead(PetscOptionItems *PetscOptionsObject, const char *name, const std::string &help,
                           const std::string &default_text, std::string &raw, PetscBool &found) {
  char buffer[256];
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buffer, default_text.c_str(), sizeof(buffer)));
  PetscCall(PetscOptionsString(name, help.c_str(), "", buffer, buffer, sizeof(buffer), nullptr));
  PetscCall(RawValue(PetscOptionsObject, name, raw, found));
  PetscFunctionReturn(0);
}

} // namespace

RealRange RealRange::Whole(double lo, double hi) {
  RealRange range{lo, hi};
  range.whole = true;
  return range;
}

bool RealRange::Contains(double value) const {
  const double a = lo * scale, b = hi * scale;
  return (lo_open ? value > a : value >= a) && (hi_open ? value < b : value <= b) &&
         (!whole || value == std::floor(value));
}

std::string RealRange::Relative() const {
  return Interval(lo, hi, lo_open, hi_open) + (unit ? std::string(" x ") + unit : "");
}

std::string RealRange::Absolute() const {
  if (!unit) return Interval(lo, hi, lo_open, hi_open);
  return Interval(lo * scale, hi * scale, lo_open, hi_open) + " (" + Relative() + ", " + unit + " " +
         FormatNumber(scale) + ")";
}

PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                           const RealRange &range, double &value, PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  // A relative range lists its default in the range's unit ("0.1 x body diagonal"), not as a bare number.
  const std::string default_text =
      range.unit && range.scale != 0 ? FormatNumber(value / range.scale) + " x " + range.unit : FormatNumber(value);
  PetscCall(ListAndRead(PetscOptionsObject, name,
                        std::string(help) + "; range " + range.Relative() + (range.whole ? ", whole numbers" : ""),
                        default_text, raw, found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCall(CheckRealValue(comm, name, raw, range, value));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckRealValue(MPI_Comm comm, const std::string &name, const std::string &raw, const RealRange &range,
                              double &value) {
  const char *kind = range.whole ? "a whole number" : "a number";
  // " in [0, 1]"; nothing for a range without bounds (any finite number).
  const std::string in = std::isinf(range.lo) && std::isinf(range.hi) ? "" : " in " + range.Absolute();
  PetscFunctionBeginUser;
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT, "%s is given without a value; expected %s%s", name.c_str(),
             kind, in.c_str());
  const auto parsed = ParseFinite(raw);
  PetscCheck(parsed, comm, PETSC_ERR_USER_INPUT, "%s %s is invalid; expected %s%s", name.c_str(), raw.c_str(),
             range.whole ? "a whole number" : REAL_GRAMMAR, in.c_str());
  PetscCheck(range.Contains(*parsed), comm, PETSC_ERR_USER_INPUT, "%s %s is %s; expected %s%s", name.c_str(),
             raw.c_str(), range.whole && *parsed != std::floor(*parsed) ? "not a whole number" : "out of range", kind,
             in.c_str());
  value = *parsed;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsInt(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscInt lo,
                          PetscInt hi, PetscInt &value, PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, std::string(help) + "; range " + range, std::to_string(value), raw,
                        found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT, "%s is given without a value; expected an integer in %s", name,
             range.c_str());
  const auto parsed = ParseInteger(raw);
  PetscCheck(parsed && *parsed >= lo && *parsed <= hi, comm, PETSC_ERR_USER_INPUT,
             "%s %s is invalid; expected an integer in %s", name, raw.c_str(), range.c_str());
  value = (PetscInt)*parsed;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsString(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                             const char *expected, std::string &value, PetscBool *set) {
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, help, value, raw, found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value; expected %s", name, expected);
  value = raw;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsStringList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                 const char *empty_means, const char *expected, std::vector<std::string> &items,
                                 PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, help, "", raw, found));
  if (set) *set = found;
  items.clear();
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value, which would leave %s; expected %s", name, empty_means, expected);
  items = Split(raw, ',');
  for (std::size_t i = 0; i < items.size(); ++i) {
    // Blanks around an item are layout ("0,2, 0,0" in an options file), as PETSc's own list readers take them.
    const auto first = items[i].find_first_not_of(" \t"), last = items[i].find_last_not_of(" \t");
    items[i] = first == std::string::npos ? "" : items[i].substr(first, last - first + 1);
    PetscCheck(!items[i].empty(), comm, PETSC_ERR_USER_INPUT,
               "%s %s has an empty item %zu (an empty list would leave %s); expected %s", name, raw.c_str(), i + 1,
               empty_means, expected);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsRealList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                               const char *empty_means, const char *expected, std::vector<double> &values,
                               PetscBool *set) {
  std::vector<std::string> items;
  PetscFunctionBeginUser;
  PetscCall(OptionsStringList(PetscOptionsObject, name, help, empty_means, expected, items, set));
  values.clear();
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto v = ParseFinite(items[i]);
    PetscCheck(v, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s %s: value %zu '%s' is invalid; expected %s",
               name, Join(items, ",").c_str(), i + 1, items[i].c_str(), REAL_GRAMMAR);
    values.push_back(*v);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsRequireValue(PetscOptionItems *PetscOptionsObject, const char *name, const char *expected) {
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(RawValue(PetscOptionsObject, name, raw, found));
  PetscCheck(!found || !raw.empty(), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value; expected %s", name, expected);
  PetscFunctionReturn(0);
}

namespace {

/// PETSc's generic options (-help lists them) that PETSc reads only in PetscFinalize or when the feature they tune
/// starts (a debugger, a shared temporary directory): given, they are not misspelt, whether or not they were read.
constexpr const char *GENERIC_READ_LATE[] = {"options_view",   "citations", "get_total_flops", "debugger_ranks",
                                             "debugger_pause", "tmp",       "shared_tmp",      "not_shared_tmp"};

/// The kinds of PETSc object whose options the saddle-point KSP (prefix contact_) and what it creates read while
/// the solve runs: the KSP and PC themselves, the factor matrix (-contact_mat_mumps_*), fieldsplit's blocks, and the
/// sub-solvers of block Jacobi/ASM, multigrid levels, redundant, telescope, LSC, redistribute, Galerkin, HMG, patch,
/// deflation and FETI-DP.
constexpr const char *SOLVER_PREFIX = "contact_";
constexpr const char *SOLVER_OBJECTS[] = {"ksp_",      "pc_",        "mat_",       "fieldsplit_", "sub_",
                                          "mg_",       "redundant_", "telescope_", "lsc_",        "redistribute_",
                                          "galerkin_", "hmg_",       "patch_",     "deflation_",  "fetidp_"};
/// The kinds of PETSc object that the solve makes or assembles without a prefix, whose generic options
/// (-vec_view, -mat_view, ...) it reads then.
constexpr const char *UNPREFIXED_OBJECTS[] = {"vec_", "mat_", "is_", "sf_", "vecscatter_", "viewer_", "draw_"};

/// Whether name (without its '-') is prefix followed by one of the object kinds.
template <std::size_t N>
bool NamesObject(const std::string &name, const std::string &prefix, const char *const (&objects)[N]) {
  return name.rfind(prefix, 0) == 0 && std::any_of(std::begin(objects), std::end(objects), [&](const char *k) {
           return name.compare(prefix.size(), std::strlen(k), k) == 0;
         });
}

} // namespace

bool IsSolverOption(const std::string &name) { return NamesObject(name, SOLVER_PREFIX, SOLVER_OBJECTS); }

PetscErrorCode CheckUnusedOptions(MPI_Comm comm, UnusedOptions when) {
  PetscBool refuse = PETSC_TRUE;
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-options_left", &refuse, nullptr));
  std::set<std::string> mine; // "-name value" of the options this rank has not read
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i];
    if (std::find(std::begin(GENERIC_READ_LATE), std::end(GENERIC_READ_LATE), name) != std::end(GENERIC_READ_LATE))
      continue;
    if (when == UnusedOptions::AFTER_SETUP &&
        (IsSolverOption(name) || NamesObject(name, "", UNPREFIXED_OBJECTS)))
      continue;
    mine.insert("-" + name + (values[i] ? std::string(" ") + values[i] : ""));
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  // Every rank holds the same options; an option counts as unused when no rank has read it (rank 0's list, agreed).
  std::string list = Join(std::vector<std::string>(mine.begin(), mine.end()), "\n");
  PetscCall(Broadcast(comm, 0, list));
  const std::vector<std::string> candidates = list.empty() ? std::vector<std::string>() : Split(list, '\n');
  std::vector<int> unused(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    unused[i] = mine.count(candidates[i]) ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, unused.data(), (int)unused.size(), MPI_INT, MPI_LAND, comm));
  std::vector<std::string> refused;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!unused[i]) continue;
    std::string origin;
    if (refuse) PetscCall(OptionOrigin(candidates[i].substr(0, candidates[i].find(' ')), origin));
    refused.push_back(candidates[i] + (origin.empty() ? "" : " (" + origin + ")"));
  }
  PetscCheck(!refuse || refused.empty(), comm, PETSC_ERR_USER_INPUT,
             "%s %s set but never read (misspelt, or not an option of this run); expected only options that this run "
             "reads (-help lists them; -options_left 0 lets unread options pass)",
             refused.size() == 1 ? "option" : "options",
             (Join(refused, ", ") + (refused.size() == 1 ? " is" : " are")).c_str());
  // PETSc's own report in PetscFinalize would list them again.
  if (when == UnusedOptions::AFTER_SOLVE) PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
  PetscFunctionReturn(0);
}

namespace {

/// An option's value for a message.
const char *ValueText(const std::string &value) { return value.empty() ? "no value" : value.c_str(); }

/// The edit distance between a and b (insertions, deletions, substitutions).
std::size_t EditDistance(const std::string &a, const std::string &b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

} // namespace

PetscErrorCode CheckCommandLine(int argc, char **argv) {
  PetscFunctionBeginUser;
  // PETSc's reading of the arguments (PetscOptionsInsertArgs): these take the next argument whatever it is, and
  // -prefix_pop none; any other key takes the next argument when that is not a key.
  static const char *const WITH_OPERAND[] = {"-options_file", "-options_file_yaml", "-options_string_yaml",
                                             "-prefix_push"};
  struct Given {
    std::string spelling, value; // as on the command line
    int position;
  };
  std::map<std::string, Given> given; // option (lower case, as PETSc compares names) -> where it is given
  std::vector<std::string> prefixes;  // -prefix_push / -prefix_pop
  int last_file = 0;                  // the position of the last -options_file
  for (int i = 1; i < argc; ++i) {
    PetscBool key;
    PetscCall(PetscOptionsValidKey(argv[i], &key));
    const std::string arg = argv[i];
    if (!key) {
      const bool options_file = EndsWith(arg, ".yml") || EndsWith(arg, ".yaml") || EndsWith(arg, ".txt") ||
                                EndsWith(arg, ".opts");
      SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
              "unexpected argument '%s': every input is an option, -name value%s", arg.c_str(),
              options_file ? ("; to read this case file, give -options_file " + arg).c_str() : "");
    }
    const std::string name = arg.substr(1);
    if (name != "options_file" && EditDistance(name, "options_file") <= 2)
      SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "unknown option %s; expected -options_file FILE",
              arg.c_str());
    const bool with_operand = std::find_if(std::begin(WITH_OPERAND), std::end(WITH_OPERAND),
                                           [&](const char *k) { return arg == k; }) != std::end(WITH_OPERAND);
    if (arg == "-prefix_push" && i + 1 < argc) prefixes.push_back(argv[i + 1]);
    if (arg == "-options_file" || arg == "-options_file_yaml") last_file = i;
    if (arg == "-prefix_pop" && !prefixes.empty()) prefixes.pop_back();
    std::string value;
    if (with_operand) {
      ++i;
    } else if (arg != "-prefix_pop" && i + 1 < argc) {
      PetscBool next_key;
      PetscCall(PetscOptionsValidKey(argv[i + 1], &next_key));
      if (!next_key) value = argv[++i];
    }
    // The same option twice: PETSc keeps the last value without a word (-bc_traction twice drops the first load).
    if (with_operand || arg == "-prefix_pop") continue;
    const std::string spelling = "-" + Join(prefixes, "") + name;
    const auto [first, fresh] = given.emplace(LowerCase(spelling), Given{spelling, value, i});
    PetscCheck(fresh, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
               "option %s is given twice on the command line (%s, then %s), and only one value would be used; "
               "expected each option once (a value on the command line overrides the same option's in an "
               "-options_file before it or in PETSC_OPTIONS)",
               spelling.c_str(), ValueText(first->second.value), ValueText(value));
  }
  // PETSc reads each -options_file where it stands: a file after an option of the command line that sets it again
  // replaces its value without a word (-bc_traction top:0:-1.25 -options_file options/hertz.yml ran the file's load).
  // The options' final values, read without marking them used (PetscOptionsGetAll), tell.
  if (last_file > 0) {
    char *all;
    PetscCall(PetscOptionsGetAll(nullptr, &all));
    std::map<std::string, std::string> final_values;
    std::istringstream words(all);
    PetscCall(PetscFree(all));
    std::string word, current;
    while (words >> word) {
      PetscBool key;
      PetscCall(PetscOptionsValidKey(word.c_str(), &key));
      if (key) {
        current = LowerCase(word);
        final_values[current] = "";
      } else if (!current.empty()) {
        final_values[current] = word;
      }
    }
    for (const auto &[option, g] : given) {
      const auto it = final_values.find(option);
      PetscCheck(g.position > last_file || it == final_values.end() || it->second == g.value, PETSC_COMM_WORLD,
                 PETSC_ERR_USER_INPUT,
                 "option %s %s on the command line is replaced by %s from an -options_file given after it; expected "
                 "the option after the -options_file whose value it is to override", g.spelling.c_str(),
                 ValueText(g.value), ValueText(it->second));
    }
  }
  PetscFunctionReturn(0);
}

namespace {

/// The options files that the words name (-options_file FILE, -options_file_yaml FILE), appended to files.
void NamedOptionsFiles(const std::vector<std::string> &words, std::vector<std::pair<std::string, std::string>> &files) {
  for (std::size_t i = 0; i + 1 < words.size(); ++i)
    if ((words[i] == "-options_file" || words[i] == "-options_file_yaml") && words[i + 1][0] != '-')
      files.emplace_back(words[i], words[i + 1]), ++i;
}

/// The words of a plain options file, without its comments (PETSc's syntax: '#' starts a comment).
std::vector<std::string> PlainFileWords(const std::string &path) {
  std::vector<std::string> words;
  std::ifstream in(path);
  std::string line, word;
  while (std::getline(in, line)) {
    std::istringstream items(line.substr(0, line.find('#')));
    while (items >> word) words.push_back(word);
  }
  return words;
}

/// Walks the documents of a YAML file as PETSc's reader does (src/sys/objects/optionsyaml.c): a scalar value sets
/// -PREFIXkey, a mapping value or a mapping in a sequence pushes the prefix key_, a merge key '<<' keeps the prefix, a
/// '$$' key sets nothing. Finds what PETSc would take without a word: an option set twice in the file, in one document
/// or in two ('---' between them; PETSc keeps the last value and drops the other, where YAML wants unique keys; the
/// one order it allows is a merge followed by the key that overrides it in the same document, as YAML means it) and
/// an options_file key (PETSc stores it as an option and reads no file).
class YamlOptions {
public:
  explicit YamlOptions(std::string path) : path_(std::move(path)) {}

  /// The first problem up to document doc (the documents of the file in order) as a message naming the file, the
  /// line and the option; empty when there is none.
  std::string Problem(yaml_document_t &doc) {
    doc_ = &doc;
    if (yaml_node_t *root = yaml_document_get_root_node(&doc)) Walk(root, "", false);
    // A merge overrides nothing of a later document: a key set there again is set twice.
    for (auto &[name, setting] : seen_)
      setting.merged = false;
    return problem_;
  }

private:
  struct Setting {
    std::size_t line;
    bool merged;
  };

  static const char *Text(const yaml_node_t *node) { return reinterpret_cast<const char *>(node->data.scalar.value); }

  void Set(const std::string &name, const yaml_node_t *key, bool merged) {
    if (!problem_.empty()) return;
    const std::size_t line = key->start_mark.line + 1;
    if (name == "-options_file" || name == "-options_file_yaml") {
      problem_ = path_ + ", line " + std::to_string(line) + ": " + name.substr(1) +
                 " in a YAML file is not read (PETSc would keep it as an unused option); expected each options file "
                 "on the command line with its own -options_file (a later one overrides an earlier one)";
      return;
    }
    const auto [it, first] = seen_.emplace(name, Setting{line, merged});
    if (first) return;
    if (it->second.merged && !merged) { // an explicit key after a merge overrides it, as YAML means
      it->second = {line, merged};
      return;
    }
    const std::string first_line = std::to_string(it->second.line), this_line = std::to_string(line);
    if (merged)
      problem_ = path_ + ", line " + first_line + ": option " + name + " is set again by a later merge '<<' (its " +
                 "value on line " + this_line + "), which PETSc would keep; expected the merge before the keys that " +
                 "override it";
    else
      problem_ = path_ + ", line " + this_line + ": option " + name + " is set again (first on line " + first_line +
                 "); expected each option once per file, in all its documents (PETSc would silently keep the last "
                 "value)";
  }

  void Walk(yaml_node_t *node, const std::string &prefix, bool merged) {
    if (!node || node->type != YAML_MAPPING_NODE || !problem_.empty()) return; // PETSc reports other shapes
    for (yaml_node_pair_t *pair = node->data.mapping.pairs.start; pair < node->data.mapping.pairs.top; ++pair) {
      yaml_node_t *key = yaml_document_get_node(doc_, pair->key), *value = yaml_document_get_node(doc_, pair->value);
      if (!key || !value || key->type != YAML_SCALAR_NODE) return;
      const std::string k = Text(key);
      if (k == "<<") {
        if (value->type == YAML_MAPPING_NODE) Walk(value, prefix, true);
        else if (value->type == YAML_SEQUENCE_NODE)
          for (yaml_node_item_t *item = value->data.sequence.items.start; item < value->data.sequence.items.top;
               ++item)
            Walk(yaml_document_get_node(doc_, *item), prefix, true);
        continue;
      }
      if (k.rfind("$$", 0) == 0) continue;
      if (value->type == YAML_MAPPING_NODE) {
        Walk(value, prefix + k + "_", merged);
        continue;
      }
      if (value->type == YAML_SEQUENCE_NODE)
        for (yaml_node_item_t *item = value->data.sequence.items.start; item < value->data.sequence.items.top; ++item)
          Walk(yaml_document_get_node(doc_, *item), prefix + k + "_", merged);
      Set("-" + prefix + k, key, merged);
    }
  }

  yaml_document_t *doc_ = nullptr;
  const std::string path_;
  std::map<std::string, Setting> seen_;
  std::string problem_;
};

/// What PETSc would take silently from the YAML options file path (YamlOptions), or its syntax error with the line,
/// as a message naming key (the option that gave the file); empty when there is nothing.
std::string YamlFileProblem(const std::string &key, const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  yaml_parser_t parser;
  if (!yaml_parser_initialize(&parser)) return "";
  yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char *>(text.data()), text.size());
  std::string problem;
  YamlOptions options(path);
  for (bool more = true; more && problem.empty();) {
    yaml_document_t doc;
    if (!yaml_parser_load(&parser, &doc)) {
      // A syntax error: named here with its line, as PETSc's own report names neither the option nor the line.
      problem = key + " " + path + ", line " + std::to_string(parser.problem_mark.line + 1) + ", column " +
                std::to_string(parser.problem_mark.column + 1) + ": " + (parser.problem ? parser.problem : "error") +
                (parser.context ? std::string(" ") + parser.context : std::string()) + "; expected a valid YAML file";
      break;
    }
    more = yaml_document_get_root_node(&doc) != nullptr;
    problem = options.Problem(doc);
    yaml_document_delete(&doc);
  }
  yaml_parser_delete(&parser);
  return problem;
}

} // namespace

std::string OptionsFileProblem(int argc, char **argv, std::string &files) {
  // The files of the command line, of PETSC_OPTIONS, and those that a plain options file names in turn (PETSc opens
  // a nested one on every rank: an unreadable one would be reported by each of them).
  std::vector<std::pair<std::string, std::string>> named; // (option, path)
  NamedOptionsFiles(std::vector<std::string>(argv + 1, argv + argc), named);
  if (const char *env = std::getenv("PETSC_OPTIONS")) {
    std::istringstream items(env);
    std::vector<std::string> words;
    for (std::string word; items >> word;) words.push_back(word);
    NamedOptionsFiles(words, named);
  }
  files.clear();
  for (std::size_t k = 0; k < named.size() && k < 100; ++k) {
    const auto [key, path] = named[k];
    files += (files.empty() ? "" : ", ") + path;
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    std::string problem;
    if (!std::filesystem::exists(status)) problem = "no such file";
    else if (std::filesystem::is_directory(status)) problem = "it is a directory";
    else if (!std::ifstream(path)) problem = "it cannot be read";
    if (!problem.empty())
      return key + " " + path + ": " + problem + "; expected a readable YAML or PETSc options file";
    const bool yaml = key == "-options_file_yaml" || EndsWith(path, ".yml") || EndsWith(path, ".yaml");
    if (!yaml) NamedOptionsFiles(PlainFileWords(path), named);
    else if (const std::string taken = YamlFileProblem(key, path); !taken.empty()) return taken;
  }
  return "";
}

} // namespace signorini
