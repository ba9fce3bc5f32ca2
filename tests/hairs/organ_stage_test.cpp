// The organs' stages as the pipeline sees them (organ_stage.h): a list in a fixed order, each
// stage with its own settings, copied deeply with the model's options, and options that parse on
// one command without clashing.
#include "hirsute/hairs/organ_stage.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <set>
#include <string>

namespace hirsute {
namespace {

TEST(OrganStages, EachStageHasItsActivityAndItsSettings) {
  const auto stages = organStages();
  // The three organs', then the passes over what they placed (the coats laid shingled).
  ASSERT_EQ(stages.size(), 4u);
  std::set<std::string> activities;
  for (const OrganStage* stage : stages) {
    activities.insert(stage->activity());
    const auto settings = stage->defaultOptions();
    ASSERT_NE(settings, nullptr);
    EXPECT_TRUE(settings->enabled);
  }
  EXPECT_EQ(activities,
            (std::set<std::string>{"placing hairs", "growing feathers", "growing fur",
                                   "shingling feathers"}));
  // The hairs are placed before the feathers' coats, and the fur last.
  EXPECT_STREQ(stages[0]->activity(), "placing hairs");
  EXPECT_STREQ(stages[2]->activity(), "growing fur");
  EXPECT_STREQ(stages[3]->activity(), "shingling feathers");
}

TEST(OrganStages, OptionsSwitchEachOrganOffOnItsOwn) {
  OrganOptionsSet settings;
  ASSERT_EQ(settings.size(), organStages().size());
  CLI::App command;
  for (std::size_t k = 0; k < settings.size(); ++k)
    organStages()[k]->addOptions(command, settings[k]);
  command.parse(
      std::vector<std::string>{"3", "--droplets", "--no-fur"});  // CLI11 reads from the back
  EXPECT_TRUE(settings[0].enabled);
  EXPECT_TRUE(settings[1].enabled);
  EXPECT_FALSE(settings[2].enabled);
}

TEST(OrganStages, CopiedSettingsAreTheirOwn) {
  OrganOptionsSet settings;
  OrganOptionsSet copy = settings;
  copy[1].enabled = false;
  EXPECT_TRUE(settings[1].enabled);
  EXPECT_FALSE(copy[1].enabled);
  settings = copy;
  copy[1].enabled = true;
  EXPECT_FALSE(settings[1].enabled);
}

TEST(OrganStages, ABadOptionValueIsRefused) {
  OrganOptionsSet settings;
  CLI::App command;
  for (std::size_t k = 0; k < settings.size(); ++k)
    organStages()[k]->addOptions(command, settings[k]);
  EXPECT_THROW(command.parse(std::vector<std::string>{"nan", "--droplet-radius"}),
               CLI::ValidationError);
}

}  // namespace
}  // namespace hirsute
