#include "hirsute/hairs/plant/hair_live.h"

namespace hirsute {
namespace {

class LiveHairs final : public LiveOrgan {
 public:
  void take(const Scene&, const ViewSettings&) override {}
};

class HairLiveType final : public LiveOrganType {
 public:
  const char* name() const override { return "hairs"; }
  char showKey() const override { return 'H'; }
  std::unique_ptr<LiveOrgan> make(LiveOrganHost&) const override {
    return std::make_unique<LiveHairs>();
  }
};

}  // namespace

const LiveOrganType& hairLive() {
  static const HairLiveType type;
  return type;
}

}  // namespace hirsute
