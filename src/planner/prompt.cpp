#include "sims/planner/prompt.h"

#include <fstream>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/planner/text.h"

namespace sims::planner {

std::string ReadPromptTemplate(const std::string& file) {
  std::filesystem::path p = file;
  if (p.is_relative()) p = ConfigPath(file);
  std::ifstream in(p, std::ios::binary);
  if (!in) ThrowInputError(p.string(), "", "a readable prompt template", "no such file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string FillPrompt(std::string text, const std::map<std::string, std::string>& values) {
  for (const auto& [key, value] : values) {
    const std::string marker = "{{" + key + "}}";
    for (std::size_t pos = 0; (pos = text.find(marker, pos)) != std::string::npos;
         pos += value.size())
      text.replace(pos, marker.size(), value);
  }
  return text;
}

std::map<std::string, std::string> VocabularyPromptValues(const Vocabulary& v) {
  std::vector<std::string> skills, styles;
  for (const SkillSpec& s : v.skills) {
    skills.push_back(s.name + (s.aliases.empty() ? "" : " (also " + s.aliases.front() + ")"));
    std::vector<std::string> texts;
    for (const StyleAxis& axis : s.axes)
      for (const StyleValue& val : axis.values)
        texts.push_back(val.text.empty() ? val.id : val.text);
    styles.push_back("- " + s.name + ": " + Join(texts, "; "));
  }
  return {{"skills", Join(skills, ", ")},
          {"furniture", v.FurnitureList()},
          {"emotions", v.EmotionList()},
          {"rooms", v.RoomTypeList()},
          {"styles", Join(styles, "\n")}};
}

}  // namespace sims::planner
