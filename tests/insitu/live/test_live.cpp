// The live page's parts without a job: the feed turns handed-over pictures into the PNGs and the
// state it serves; the server starts on a free port with a random token, and a port taken is a
// start-up error that names it; the page says its address at any log level. Its rules over
// HTTP: tests/integration/live/.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "insitu/live/live_feed.h"
#include "insitu/live/live_server.h"
#include "insitu/outputs/formats/png_image.h"
#include "insitu/runtime/live_page.h"
#include "tests/support/error_message.h"
#include "tests/support/log_capture.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

// The feed's snapshot once its state holds `text` (it looks for new steps every 50 ms, at a
// lower priority: up to 10 s on a loaded machine).
std::shared_ptr<const LiveSnapshot> snapshot_with(const LiveFeed& feed, const std::string& text) {
  for (int i = 0; i < 1000; ++i) {
    auto s = feed.snapshot();
    if (s->state.find(text) != std::string::npos) return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return feed.snapshot();
}

TEST(LiveFeed, ServesTheLatestPictureAsTheOutputsPngAndTheStepsPasses) {
  LiveFeed feed({"main", "side"});
  EXPECT_NE(feed.snapshot()->state.find("\"step\":-1"), std::string::npos);
  PicturePool pool(4);
  FloatImage drawn(8, 4);
  for (std::size_t i = 0; i < drawn.rgba.size(); ++i) drawn.rgba[i] = float(i % 7) / 6.0f;
  const FloatImage expected = drawn;
  SharedPicture picture = pool.take(drawn);
  FrameStats stats;
  stats.add_time("shade", 2.5);
  ViewResult views[2];
  views[0] = {
      .name = "main", .picture = picture.get(), .shared_picture = &picture, .stats = &stats};
  views[1] = {.name = "side"};  // failed this step: no picture
  const std::pair<const char*, double> solver[] = {{"classify", 1.0}, {"outputs", 0.5}};
  feed.publish({40, 0.25, 1000, 6.0, views, solver});

  const auto s = snapshot_with(feed, "\"step\":40");
  EXPECT_NE(s->state.find("\"running\":true"), std::string::npos) << s->state;
  EXPECT_NE(s->state.find("\"particles\":1000"), std::string::npos) << s->state;
  EXPECT_NE(s->state.find("\"passes\":[\"classify\",\"outputs\",\"shade\"]"), std::string::npos)
      << s->state;
  EXPECT_NE(s->state.find("\"history\":[[40,1,0.5,2.5]]"), std::string::npos) << s->state;
  EXPECT_NE(s->state.find("{\"name\":\"main\",\"step\":40,\"width\":8,\"height\":4}"),
            std::string::npos)
      << s->state;
  ASSERT_TRUE(s->pictures[0]);
  EXPECT_EQ(*s->pictures[0], encode_png(linear_to_srgb8(expected.rgba, 8, 4)));
  EXPECT_FALSE(s->pictures[1]);

  feed.finish();
  EXPECT_NE(snapshot_with(feed, "\"running\":false")->state.find("\"running\":false"),
            std::string::npos);
}

// Steps that come faster than LiveFeed::kSnapshotEveryMs: the snapshot made again no sooner
// than that after the last, from the newest step (none left showing an older picture), and at
// once when the job ends.
TEST(LiveFeed, SnapshotsAtMostEveryIntervalTheNewestStepAlways) {
  PicturePool pool(4);  // first: it outlives the feed's references, whatever fails
  LiveFeed feed({"main"});
  auto step = [&](std::int64_t n, float value) {
    FloatImage drawn(4, 2);
    std::fill(drawn.rgba.begin(), drawn.rgba.end(), value);
    SharedPicture picture = pool.take(drawn);
    ViewResult views[1];
    views[0] = {.name = "main", .picture = picture.get(), .shared_picture = &picture};
    feed.publish({n, 0.1 * double(n), 10, 1.0, views, {}});
  };
  auto png = [](float value) {
    FloatImage expected(4, 2);
    std::fill(expected.rgba.begin(), expected.rgba.end(), value);
    return encode_png(linear_to_srgb8(expected.rgba, 4, 2));
  };
  const auto start = std::chrono::steady_clock::now();
  step(1, 0.1f);
  ASSERT_EQ(*snapshot_with(feed, "{\"name\":\"main\",\"step\":1,")->pictures[0], png(0.1f));
  step(2, 0.2f);
  step(3, 0.3f);
  const auto shown = snapshot_with(feed, "{\"name\":\"main\",\"step\":3,");
  const double waited_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_NE(shown->state.find("{\"name\":\"main\",\"step\":3,"), std::string::npos) << shown->state;
  EXPECT_EQ(*shown->pictures[0], png(0.3f));
  EXPECT_GE(waited_ms, LiveFeed::kSnapshotEveryMs);

  step(4, 0.4f);
  feed.finish();
  const auto last = snapshot_with(feed, "\"running\":false");
  EXPECT_NE(last->state.find("{\"name\":\"main\",\"step\":4,"), std::string::npos) << last->state;
  EXPECT_EQ(*last->pictures[0], png(0.4f));
  // Step 2, handed over before the feed took step 1's successor, still counts.
  EXPECT_NE(last->state.find("\"render_steps\":4"), std::string::npos) << last->state;
}

TEST(LiveServer, ListensOnAFreePortWithARandomTokenAndNamesAPortTaken) {
  LiveFeed feed({"main"});
  LiveConfig config;
  config.enabled = true;
  LiveServer server(config, feed);
  EXPECT_GT(server.port(), 0);
  EXPECT_EQ(server.token().size(), 64u);
  EXPECT_EQ(server.token().find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(server.url(),
            "http://127.0.0.1:" + std::to_string(server.port()) + "/?token=" + server.token());
  LiveServer other(config, feed);
  EXPECT_NE(other.token(), server.token());

  config.port = server.port();
  const std::string e = test::error_message([&] { LiveServer taken(config, feed); });
  EXPECT_NE(e.find("live page: cannot listen on 127.0.0.1:" + std::to_string(server.port()) +
                   ": Address already in use (another program"),
            std::string::npos)
      << e;
}

// The page's address, with its token, is the only way in: said even where the log level hides
// warnings.
TEST(LivePage, SaysItsAddressAtAnyLogLevel) {
  for (const LogLevel level : {LogLevel::warning, LogLevel::error}) {
    test::LogCapture log;  // restores the level it found
    set_log_level(level);
    LiveConfig config;
    config.enabled = true;
    const LivePage page(config, {"main"}, true, nullptr);
    EXPECT_NE(log.all().find("live page: http://127.0.0.1:"), std::string::npos)
        << int(level) << ": " << log.all();
  }
}

}  // namespace
}  // namespace voxspan
