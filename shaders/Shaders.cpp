#include "shaders/Shaders.h"

#include <set>
#include <sstream>
#include <stdexcept>

namespace geocean::shaders {

std::optional<EmbeddedShader> find(std::string_view name) {
  for (const EmbeddedShader* s = detail::kEmbedded; s->name; ++s)
    if (name == s->name) return *s;
  return std::nullopt;
}

std::vector<std::string> names() {
  std::vector<std::string> out;
  for (const EmbeddedShader* s = detail::kEmbedded; s->name; ++s) out.emplace_back(s->name);
  return out;
}

namespace {
void expand(std::string_view name, std::set<std::string>& seen, std::ostringstream& out,
            std::string_view includedFrom) {
  if (!seen.insert(std::string(name)).second) return;
  auto s = find(name);
  if (!s)
    throw std::runtime_error("shader '" + std::string(name) + "' is not embedded" +
                             (includedFrom.empty() ? std::string() : " (included from " + std::string(includedFrom) + ")"));
  std::istringstream in(s->text);
  std::string line;
  int lineNo = 0;
  out << "#line 1\n";
  while (std::getline(in, line)) {
    ++lineNo;
    const auto p = line.find("#include");
    if (p != std::string::npos && line.find_first_not_of(" \t") == p) {
      const auto q1 = line.find('"', p), q2 = line.find('"', q1 + 1);
      if (q1 == std::string::npos || q2 == std::string::npos)
        throw std::runtime_error(std::string(s->sourcePath) + ":" + std::to_string(lineNo) + ": malformed #include");
      expand(line.substr(q1 + 1, q2 - q1 - 1), seen, out, s->sourcePath);
      out << "#line " << lineNo + 1 << "\n";
      continue;
    }
    out << line << '\n';
  }
}
}  // namespace

std::string assemble(std::string_view stageName, const std::vector<std::string>& defines) {
  std::ostringstream out;
  out << "#version 450 core\n";
  out << "#define GEOCEAN_REFLECTION_REACH_M " << std::fixed << kReflectionReachM << '\n';
  for (const auto& d : defines) out << "#define " << d << '\n';
  std::set<std::string> seen;
  expand(stageName, seen, out, "");
  return out.str();
}

}  // namespace geocean::shaders
