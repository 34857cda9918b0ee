// The one contract: its JSON reader and writer, its names and messages, its resolution.
#include "oblique/cases/contract.h"

#include <gtest/gtest.h>

#include <iterator>
#include <string>
#include <utility>

#include "oblique/protocol/names.h"

namespace oblique {
namespace {

using cases::Defect;
using cases::Family;
using cases::Place;
using cases::Property;
using cases::StatusContract;

TEST(Contract, readsEveryField) {
  const Expected<Contract> c = read_contract(R"({
    "families": ["perspective", "infinite"], "conventions": ["zero_one"],
    "places": ["typical", "scaled"], "planes": "unit", "statuses": ["camera_not_behind_plane"],
    "defects": ["singular"], "properties": ["no_clipping"], "row3_accuracy": false})");
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->families, (std::vector<Family>{Family::perspective, Family::infinite}));
  EXPECT_EQ(c->conventions, std::vector<Convention>{Convention::zero_one});
  EXPECT_EQ(c->places, (std::vector<Place>{Place::typical, Place::scaled}));
  EXPECT_EQ(c->planes, Planes::unit);
  EXPECT_EQ(c->statuses, StatusContract::exact);
  EXPECT_EQ(c->refusals, std::vector<Status>{Status::camera_not_behind_plane});
  EXPECT_EQ(c->defects, std::vector<Defect>{Defect::singular});
  EXPECT_EQ(c->properties, std::vector<Property>{Property::no_clipping});
  EXPECT_EQ(c->row3_accuracy, false);
}

TEST(Contract, theWriterGivesBackWhatTheReaderReads) {
  for (const char* text :
       {"{}", R"({"statuses": "answers_only", "planes": "unit", "conventions": ["all"]})",
        R"({"families": ["x_flipped"], "statuses": ["out_of_range", "invalid_input"]})",
        R"({"exclude": ["general", "near_eye", "non_finite"], "row3_accuracy": false})",
        R"({"statuses": "any_refusal", "properties": ["near_is_clip_plane"]})"}) {
    const Expected<Contract> read = read_contract(text);
    ASSERT_TRUE(read) << text << ": " << read.error();
    const std::string written = contract_json(*read);
    const Expected<Contract> again = read_contract(written);
    ASSERT_TRUE(again) << written << ": " << again.error();
    EXPECT_EQ(contract_json(*again), written) << text;
    EXPECT_EQ(again->families, read->families) << written;
    EXPECT_EQ(again->conventions, read->conventions) << written;
    EXPECT_EQ(again->places, read->places) << written;
    EXPECT_EQ(again->planes, read->planes) << written;
    EXPECT_EQ(again->statuses, read->statuses) << written;
    EXPECT_EQ(again->refusals, read->refusals) << written;
    EXPECT_EQ(again->defects, read->defects) << written;
    EXPECT_EQ(again->properties, read->properties) << written;
    EXPECT_EQ(again->row3_accuracy, read->row3_accuracy) << written;
  }
}

TEST(Contract, refusesUnknownNamesWithTheKnownOnesAndTheClosest) {
  const struct {
    const char* text;
    const char* message;
  } cases[] = {
      {R"({"families": ["perspectve"]})",
       "unknown family \"perspectve\" (did you mean perspective?; known: perspective, off_axis"},
      {R"({"conventions": ["opengl"]})", "unknown convention \"opengl\" (known: gl, zero_one"},
      {R"({"place": ["typical"]})", "unknown field \"place\" (did you mean places?"},
      {R"({"statuses": "exactly"})", "unknown status contract \"exactly\" (did you mean exact?"},
      {R"({"statuses": ["ok"]})", "unknown refusal status \"ok\""},
      {R"({"exclude": ["infinte"]})", "did you mean infinite?"},
      {R"({"planes": "normalised"})", "\"planes\" is \"unit\" or \"any\""},
      {R"({"answers_only": true})", "\"statuses\": \"answers_only\""},
      {R"({"families": "perspective"})", "\"families\" is a list of names, not a string"},
      {R"({"row3_accuracy": 1})", "\"row3_accuracy\" is true or false"},
      {R"({"families": [], "families": []})", "field \"families\" given twice"},
      {R"([1, 2])", "a contract is a JSON object, not an array"},
      {R"({"families": [)", "syntax error"},
  };
  for (const auto& c : cases) {
    const Expected<Contract> read = read_contract(c.text);
    ASSERT_FALSE(read) << c.text;
    EXPECT_NE(read.error().find(c.message), std::string::npos)
        << c.text << "\n  said: " << read.error() << "\n  expected: " << c.message;
  }
}

// A contract file that never ends, a folder, a missing file: refused with the reason, never read
// whole (/dev/zero once aborted `oblique verify --contract` with std::bad_alloc).
TEST(Contract, aFileThatIsNoContractIsRefusedWithTheReason) {
  for (const auto& [path, reason] :
       {std::pair<std::string, std::string>{"/dev/zero", "larger than 1048576 bytes"},
        {::testing::TempDir(), "is a directory"},
        {"/no/such/contract.json", "cannot open"}}) {
    const Expected<Contract> c = read_contract_file(path);
    ASSERT_FALSE(c) << path;
    EXPECT_NE(c.error().find("the contract file " + path + ": " + reason), std::string::npos)
        << c.error();
  }
}

TEST(Contract, excludeRemovesFromFilledListsAndRefusesEmptyOnes) {
  const Expected<Contract> c = exclude(Contract{}, {"general", "scaled", "singular"});
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->families.size(), std::size(cases::all_families) - 1);
  EXPECT_EQ(std::count(c->families.begin(), c->families.end(), Family::general), 0);
  EXPECT_EQ(std::count(c->places.begin(), c->places.end(), Place::scaled), 0);
  EXPECT_EQ(std::count(c->defects.begin(), c->defects.end(), Defect::singular), 0);
  Contract one;
  one.families = {Family::general};
  const Expected<Contract> none = exclude(one, {"general"});
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error(), "exclude leaves no family");
}

// The engine preset: the perspective shape's families (flipped ones included), unit planes,
// answers only; the other fields change it wherever the preset stands.
TEST(Contract, theEnginePresetIsReadFirstAndChangedByTheOtherFields) {
  const Contract engine = engine_contract();
  EXPECT_EQ(engine.families, std::vector<Family>(std::begin(cases::engine_families),
                                                 std::end(cases::engine_families)));
  EXPECT_EQ(engine.planes, Planes::unit);
  EXPECT_EQ(engine.statuses, StatusContract::answers_only);
  EXPECT_TRUE(engine.conventions.empty());
  for (const char* text : {R"({"preset": "engine", "conventions": ["reversed_z"]})",
                           R"({"conventions": ["reversed_z"], "preset": ["engine"]})"}) {
    const Expected<Contract> c = read_contract(text);
    ASSERT_TRUE(c) << text << ": " << c.error();
    EXPECT_EQ(c->families, engine.families) << text;
    EXPECT_EQ(c->planes, Planes::unit) << text;
    EXPECT_EQ(c->statuses, StatusContract::answers_only) << text;
    EXPECT_EQ(c->conventions, std::vector<Convention>{Convention::reversed_z}) << text;
  }
  const Expected<Contract> wider = with_field(engine, "statuses", {"any_refusal"});
  ASSERT_TRUE(wider) << wider.error();
  EXPECT_EQ(wider->statuses, StatusContract::any_refusal);
  EXPECT_EQ(wider->families, engine.families);
  for (const auto& [text, says] :
       {std::pair<std::string, std::string>{R"({"preset": "engin"})",
                                            "unknown preset \"engin\" (did you mean engine?"},
        {R"({"preset": 1})", "\"preset\" is the name of one preset"}}) {
    const Expected<Contract> c = read_contract(text);
    ASSERT_FALSE(c) << text;
    EXPECT_NE(c.error().find(says), std::string::npos) << c.error();
  }
}

TEST(Contract, aFlagReplacesItsFieldWithTheReadersChecks) {
  Expected<Contract> c = read_contract(R"({"families": ["perspective"], "planes": "unit"})");
  ASSERT_TRUE(c);
  c = with_field(std::move(*c), "families", {"infinite", "orthographic"});
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->families, (std::vector<Family>{Family::infinite, Family::orthographic}));
  EXPECT_EQ(c->planes, Planes::unit);
  c = with_field(std::move(*c), "statuses", {"answers_only"});
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->statuses, StatusContract::answers_only);
  c = with_field(std::move(*c), "statuses", {"out_of_range"});
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->statuses, StatusContract::exact);
  EXPECT_EQ(c->refusals, std::vector<Status>{Status::out_of_range});
  const Expected<Contract> wrong = with_field(*c, "places", {"near_ey"});
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().find("did you mean near_eye?"), std::string::npos) << wrong.error();
}

TEST(Contract, resolvedFillsEveryListAndTheImplementationsOwn) {
  const Contract r =
      resolved(Contract{}, {Convention::reversed_z}, StatusContract::any_refusal, true);
  EXPECT_EQ(r.families.size(), std::size(cases::all_families));
  EXPECT_EQ(r.conventions, std::vector<Convention>{Convention::reversed_z});
  EXPECT_EQ(r.places.size(), std::size(cases::all_places));
  EXPECT_EQ(r.defects.size(), std::size(cases::all_defects));
  EXPECT_EQ(r.properties, cases::Checks{}.properties);
  EXPECT_EQ(r.statuses, StatusContract::any_refusal);
  EXPECT_EQ(r.row3_accuracy, true);
  Contract unit;
  unit.planes = Planes::unit;
  const Contract u = resolved(unit, {Convention::gl}, StatusContract::exact, false);
  EXPECT_EQ(std::count(u.places.begin(), u.places.end(), Place::scaled), 0);
  EXPECT_EQ(u.places.size(), std::size(cases::all_places) - 1);
  Contract given;
  given.conventions = {Convention::zero_one};
  given.statuses = StatusContract::answers_only;
  given.row3_accuracy = false;
  const Contract g = resolved(given, {Convention::gl}, StatusContract::exact, true);
  EXPECT_EQ(g.conventions, std::vector<Convention>{Convention::zero_one});
  EXPECT_EQ(g.statuses, StatusContract::answers_only);
  EXPECT_EQ(g.row3_accuracy, false);
}

TEST(Names, theClosestNameIsWithinAThirdOfItsLetters) {
  const std::vector<std::string> known = {"apply", "verify", "check", "report"};
  EXPECT_EQ(protocol::closest_name("verfy", known), "verify");
  EXPECT_EQ(protocol::closest_name("vreify", known), "verify");  // two letters swapped
  EXPECT_EQ(protocol::closest_name("chek", known), "check");
  EXPECT_EQ(protocol::closest_name("rep", known), "report");  // the prefix of one
  EXPECT_EQ(protocol::closest_name("xyz", known), "");
  EXPECT_EQ(protocol::closest_name("", known), "");
  EXPECT_EQ(protocol::closest_name("appl", {"apply", "apple"}), "apply");  // the first nearest
}

}  // namespace
}  // namespace oblique
