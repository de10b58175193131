// The planner's closed vocabulary: skills (with aliases and expressible styles), furniture
// categories (aliases, affordances, importance), substitution classes, emotions and room types.
// Everything is data in configs/planner/vocabulary.json so that new furniture or styles need no
// code change; this header only indexes it.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sims/core/config.h"

namespace sims::planner {

/// The planner's script grammar: the skill vocabulary's scripted skills (core/skill_vocabulary.h),
/// in its order. Composition rules (postures, inserted walks and get-ups) are written over these.
enum class Skill { kWalk, kSit, kLie, kReach, kGetUp };
/// Number of Skill values.
inline constexpr int kNumSkills = 5;

/// Canonical lower-case name, from the skill vocabulary ("walk", "sit", "lie", "reach", "getup").
const char* SkillName(Skill skill);

/// True for sit, lie and reach (keyframes that touch an object).
inline bool IsInteraction(Skill s) {
  return s == Skill::kSit || s == Skill::kLie || s == Skill::kReach;
}

/// One value of a style axis and the caption phrases that express it.
struct StyleValue {
  std::string id;                    ///< e.g. "slow_bowed", "left", "high".
  std::vector<std::string> phrases;  ///< Lower-case caption phrases that select this value.
  std::string text;                  ///< Phrase used when the composer writes a caption.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(id));
    a->Visit(SIMS_NVP(phrases));
    a->Visit(SIMS_NVP(text));
  }
};

/// One independent axis of a skill's style (reach has hand × height, walk has gait).
struct StyleAxis {
  std::string name;                ///< Axis name ("gait", "hand", "height", ...).
  std::vector<StyleValue> values;  ///< Allowed values.
  std::string default_value;       ///< Used when neither caption nor emotion selects one.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(values));
    a->Visit(SIMS_NVP(default_value));
  }
};

/// A skill, its aliases in scripts and its style axes.
struct SkillSpec {
  std::string name;                  ///< Canonical name (walk, sit, lie, reach, getup).
  std::vector<std::string> aliases;  ///< Accepted spellings (normalised: lower case, no spaces).
  std::vector<StyleAxis> axes;       ///< Style axes; a style id joins the axis values with '_'.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(aliases));
    a->Visit(SIMS_NVP(axes));
  }
};

/// A furniture category.
struct FurnitureSpec {
  std::string name;                      ///< Canonical category (matches scene::Object::category).
  std::vector<std::string> aliases;      ///< Other names (couch, bookcase, bedside table, ...).
  std::vector<std::string> affordances;  ///< Subset of sit, lie, reach.
  bool important = true;                 ///< Lamps, vases, plants: false (cheap scene-graph nodes).
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(aliases));
    a->Visit(SIMS_NVP(affordances));
    a->Visit(SIMS_NVP(important));
  }
};

/// A symmetric substitution between two categories and its cost (0 = identical, 1 = unrelated).
struct SubstitutionSpec {
  std::string a;      ///< First category.
  std::string b;      ///< Second category.
  double cost = 0.3;  ///< Graph-edit cost of using one for the other.
  template <class A>
  void Serialize(A* a_) {
    a_->Visit(MakeNameValue("a", &a));
    a_->Visit(MakeNameValue("b", &b));
    a_->Visit(MakeNameValue("cost", &cost));
  }
};

/// An emotion with its default style per skill (used when a caption names no style).
struct EmotionSpec {
  std::string name;                           ///< happy, angry, ..., neutral.
  std::vector<std::string> aliases;           ///< depressed → sad, exhausted → tired, ...
  std::string adjective;                      ///< Word the narrative uses ("cheerful").
  std::map<std::string, std::string> styles;  ///< skill → style id default.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(aliases));
    a->Visit(SIMS_NVP(adjective));
    a->Visit(SIMS_NVP(styles));
  }
};

/// A room type and its aliases.
struct RoomTypeSpec {
  std::string name;                  ///< bedroom, living room, dining room, library.
  std::vector<std::string> aliases;  ///< kitchen → dining room, study → library, ...
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(aliases));
  }
};

/// Result of resolving a style from a caption.
struct StyleChoice {
  std::string id;                       ///< Joined axis values ("right_high").
  bool from_caption = false;            ///< True when every non-default axis came from the caption.
  std::vector<bool> axis_from_caption;  ///< Per axis: the caption named the value.
};

/// How a name outside the vocabulary was matched to a known one.
struct TermMatch {
  std::string canonical;  ///< Canonical name (a furniture category, skill, emotion or room).
  std::string how;        ///< "known", "singular", "part 'chair'", "spelling 'sofa'", ...
};

/// The whole vocabulary; load with Vocabulary::Load, then query.
class Vocabulary {
 public:
  std::vector<SkillSpec> skills;                ///< Exactly the scripted skills.
  std::vector<FurnitureSpec> furniture;         ///< Known furniture categories ("floor" included).
  std::vector<SubstitutionSpec> substitutions;  ///< Fault-tolerant category substitutions.
  std::vector<EmotionSpec> emotions;            ///< Eight emotions plus neutral.
  std::vector<RoomTypeSpec> room_types;         ///< Room types.

  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(skills));
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(substitutions));
    a->Visit(SIMS_NVP(emotions));
    a->Visit(SIMS_NVP(room_types));
  }
  /// Checks names are unique and references resolve (throws FieldError).
  void Validate() const;

  /// Loads configs/planner/vocabulary.json (or `path`) and builds the indexes.
  static Vocabulary Load(const std::filesystem::path& path = {});
  /// The default vocabulary, loaded once and cached.
  static const Vocabulary& Default();

  /// Lower-cases and removes spaces, '_' and '-' ("Sit Down" → "sitdown").
  static std::string Squash(const std::string& s);

  /// Skill for a name or alias, if known.
  std::optional<Skill> FindSkill(const std::string& name) const;
  /// Spec of a skill.
  const SkillSpec& Spec(Skill skill) const;
  /// Canonical furniture category for a name or alias ("couch" → "sofa"), if known.
  std::optional<std::string> FindFurniture(const std::string& name) const;
  /// Spec of a canonical category, or nullptr.
  const FurnitureSpec* FurnitureByName(const std::string& category) const;
  /// True when the category supports the skill (walk: always; getup: sit or lie).
  bool Affords(const std::string& category, Skill skill) const;
  /// Canonical categories that afford `skill`.
  std::vector<std::string> CategoriesAffording(Skill skill) const;
  /// Importance of a category (unknown categories are important).
  bool IsImportant(const std::string& category) const;
  /// Substitution cost between two canonical categories: 0 if equal, the table's cost if listed,
  /// nullopt if they cannot substitute each other.
  std::optional<double> SubstitutionCost(const std::string& a, const std::string& b) const;
  /// Categories that can stand in for `category`, cheapest first (excluding itself).
  std::vector<std::string> Substitutes(const std::string& category) const;
  /// Canonical emotion for a word ("depressed" → "sad"), if known.
  std::optional<std::string> FindEmotion(const std::string& word) const;
  /// Spec of a canonical emotion, or nullptr.
  const EmotionSpec* EmotionByName(const std::string& name) const;
  /// Canonical room type for a name or alias, if known.
  std::optional<std::string> FindRoomType(const std::string& name) const;
  /// Resolves a style from a caption (and extra hint words), falling back to the emotion's
  /// default and then each axis default.
  StyleChoice ResolveStyle(Skill skill, const std::string& caption,
                           const std::string& emotion) const;
  /// True when `style` is a valid style id for the skill.
  bool IsValidStyle(Skill skill, const std::string& style) const;
  /// Caption fragment for a style ("slowly with the head bowed"), for inserted keyframes.
  std::string StyleText(Skill skill, const std::string& style) const;
  /// Comma-separated canonical names (for error messages).
  std::string SkillList() const;
  /// Comma-separated furniture categories (for error messages).
  std::string FurnitureList() const;
  /// Comma-separated emotions (for error messages).
  std::string EmotionList() const;
  /// Comma-separated room types (for error messages).
  std::string RoomTypeList() const;
  /// Nearest furniture category for free text a model wrote ("wooden rocking chairs" → chair,
  /// "armchiar" → armchair): exact name or alias, singular form, the longest known part
  /// (rightmost first, the English head noun), then spelling; nullopt when nothing is close.
  std::optional<TermMatch> NearestFurniture(const std::string& text) const;
  /// Nearest skill for a verb phrase ("sitting down" → sit, "walked over" → walk).
  std::optional<TermMatch> NearestSkill(const std::string& text) const;
  /// Nearest emotion for a phrase ("very sleepy" → tired).
  std::optional<TermMatch> NearestEmotion(const std::string& text) const;
  /// Nearest room type for a phrase ("a cozy bedroom" → bedroom).
  std::optional<TermMatch> NearestRoomType(const std::string& text) const;
  /// The known name closest to `word` by edit distance among `names` ("" if none is close).
  static std::string Closest(const std::string& word, const std::vector<std::string>& names);

 private:
  void BuildIndex();
  static std::optional<TermMatch> Nearest(const std::string& text,
                                          const std::map<std::string, std::string>& index);
  std::map<std::string, Skill> skill_index_;
  std::map<std::string, std::string> furniture_index_, emotion_index_, room_index_;
};

}  // namespace sims::planner
