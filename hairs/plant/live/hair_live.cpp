#include "hirsute/hairs/plant/hair_live.h"

namespace hirsute {
namespace {

class LiveHairs final : public LiveOrgan {
 public:
  explicit LiveHairs(LiveOrganHost&) {}
  void take(const Scene&, const ViewSettings&) override {}
};

}  // namespace

const LiveOrganType& plantHairLive() {
  static const LiveOrganTypeOf<LiveHairs> type("hairs", 'H');
  return type;
}

}  // namespace hirsute
