// The options files: unreadable ones, and what PETSc would take from a YAML file without a word.
#include "signorini/options/options_files.hpp"

#include "signorini/core/parse.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include <yaml.h>

namespace signorini {

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
