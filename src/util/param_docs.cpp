#include "stocs/util/param_docs.h"

#include <fmt/format.h>

#include <algorithm>

namespace stocs {
namespace {

constexpr size_t kCommentColumn = 31;
constexpr size_t kLineWidth = 100;

std::vector<std::string> split(const std::string& key) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    parts.push_back(key.substr(start, dot - start));
    start = dot + 1;
  }
  parts.push_back(key.substr(start));
  return parts;
}

std::string allowed(const ParamInfo& info) {
  if (info.range) return info.range->str();
  if (!info.choices.empty()) return fmt::format("{}", fmt::join(info.choices, ", "));
  return "";
}

std::string comment(const ParamInfo& info) {
  std::string detail = info.unit;
  const std::string values = allowed(info);
  if (!values.empty()) detail += (detail.empty() ? "" : ", ") + values;
  return detail.empty() ? info.meaning : fmt::format("{} ({})", info.meaning, detail);
}

/// Text safe in a markdown table cell: "<name>" would be read as an HTML tag, "|" as a cell end.
std::string markdownCell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '|') {
      out += "\\|";
    } else {
      out += c;
    }
  }
  return out;
}

/// `line` with `text` as a comment from kCommentColumn on, wrapped before kLineWidth.
std::string commented(std::string line, const std::string& text) {
  const size_t column = std::max(line.size() + 1, kCommentColumn);
  std::string out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.size();
    if (column + 2 + (end - start) > kLineWidth) {
      end = text.rfind(' ', start + (kLineWidth - column - 2));
      if (end == std::string::npos || end <= start) end = text.size();
    }
    line.resize(column, ' ');
    out += line + "# " + text.substr(start, end - start) + "\n";
    line.clear();
    start = end + (end < text.size() ? 1 : 0);
  }
  return out;
}

}  // namespace

std::string paramsYaml(const DescribedParams& params, int indent) {
  std::string out;
  std::vector<std::string> open;  // the maps the previous key was in
  for (const auto& [info, value] : params) {
    std::vector<std::string> path = split(info.key);
    const std::string leaf = path.back();
    path.pop_back();
    size_t common = 0;
    while (common < open.size() && common < path.size() && open[common] == path[common]) ++common;
    // A blank line between the top-level sections.
    if (!out.empty() && common == 0 && (!path.empty() || !open.empty())) out += "\n";
    for (size_t level = common; level < path.size(); ++level) {
      out += fmt::format("{:{}}{}:\n", "", indent + 2 * static_cast<int>(level), path[level]);
    }
    open = path;
    const std::string line =
        fmt::format("{:{}}{}: {}", "", indent + 2 * static_cast<int>(path.size()), leaf,
                    value.empty() ? "\"\"" : value);
    out += commented(line, comment(info));
  }
  return out;
}

std::string paramsMarkdown(const DescribedParams& params, const std::string& key_prefix,
                           bool cli_flags) {
  std::string out = cli_flags
                        ? "| key | default | unit | allowed | meaning | `stocs` option |\n"
                          "|---|---|---|---|---|---|\n"
                        : "| key | default | unit | allowed | meaning |\n|---|---|---|---|---|\n";
  for (const auto& [info, value] : params) {
    out += fmt::format("| `{}{}` | {} | {} | {} | {} |", key_prefix, info.key,
                       value.empty() ? "\"\"" : "`" + value + "`", info.unit, allowed(info),
                       markdownCell(info.meaning));
    if (cli_flags) out += fmt::format(" `{}` |", info.cliFlag());
    out += "\n";
  }
  return out;
}

}  // namespace stocs
