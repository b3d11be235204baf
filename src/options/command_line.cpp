// The command line as PETSc reads it: stray arguments, misspelt -options_file, options given twice.
#include "signorini/options/command_line.hpp"

#include "signorini/core/parse.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace signorini {

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

/// Where an option is given on the command line.
struct Given {
  std::string spelling, value; // as on the command line
  int position;
};

/// The options given on the command line: option (lower case, as PETSc compares names) -> where it is given.
using GivenOptions = std::map<std::string, Given>;

/// Reads the arguments as PETSc does (PetscOptionsInsertArgs) into given; last_file: the position of the last
/// -options_file (0: none). Refuses a stray argument, a misspelt -options_file and an option given twice.
[[nodiscard]] PetscErrorCode ReadGiven(int argc, char **argv, GivenOptions &given, int &last_file) {
  PetscFunctionBeginUser;
  // These take the next argument whatever it is, and -prefix_pop none; any other key takes the next argument when
  // that is not a key.
  static const char *const WITH_OPERAND[] = {"-options_file", "-options_file_yaml", "-options_string_yaml",
                                             "-prefix_push"};
  std::vector<std::string> prefixes; // -prefix_push / -prefix_pop
  last_file = 0;
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
  PetscFunctionReturn(0);
}

/// The options' final values (lower-case name -> value, "" for none), read without marking them used
/// (PetscOptionsGetAll).
[[nodiscard]] PetscErrorCode FinalValues(std::map<std::string, std::string> &final_values) {
  PetscFunctionBeginUser;
  char *all;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
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
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckCommandLine(int argc, char **argv) {
  GivenOptions given;
  int last_file;
  PetscFunctionBeginUser;
  PetscCall(ReadGiven(argc, argv, given, last_file));
  // PETSc reads each -options_file where it stands: a file after an option of the command line that sets it again
  // replaces its value without a word (-bc_traction top:0:-1.25 -options_file options/hertz.yml ran the file's load).
  // The options' final values tell.
  if (last_file > 0) {
    std::map<std::string, std::string> final_values;
    PetscCall(FinalValues(final_values));
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

} // namespace signorini
