#include "libcommon/error.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace rs {
namespace {

// Collects what reaches the sink while the test lives.
class SinkRecorder {
  public:
    SinkRecorder() {
        previous_ = SetErrorSink([this](const Diagnostic& d) { messages.push_back(d.message); });
    }
    ~SinkRecorder() { SetErrorSink(std::move(previous_)); }
    std::vector<std::string> messages;

  private:
    ErrorSink previous_;
};

TEST(HeldReports, CountsInsteadOfDeliveringAndFatalOnesStillThrow) {
    SinkRecorder sink;
    {
        const HeldReports held;
        Report(Severity::Warn, {"a.ray", 3}, "first %d", 1);
        Report(Severity::Advise, {}, "second");
        EXPECT_THROW(Report(Severity::Abort, {"a.ray", 4}, "fatal"), FatalError);
        EXPECT_EQ(held.Count(), 3);
    }
    EXPECT_TRUE(sink.messages.empty());
    Report(Severity::Warn, {}, "after");
    ASSERT_EQ(sink.messages.size(), 1u);
    EXPECT_EQ(sink.messages[0], "after");
}

TEST(HeldReports, InnermostScopeCountsAndOnlyOnItsThread) {
    SinkRecorder sink;
    const HeldReports outer;
    {
        const HeldReports inner;
        Report(Severity::Warn, {}, "inner");
        EXPECT_EQ(inner.Count(), 1);
    }
    EXPECT_EQ(outer.Count(), 0);
    Report(Severity::Warn, {}, "outer");
    EXPECT_EQ(outer.Count(), 1);
    std::thread other([] { Report(Severity::Warn, {}, "other thread"); });
    other.join();
    ASSERT_EQ(sink.messages.size(), 1u);
    EXPECT_EQ(sink.messages[0], "other thread");
}

}  // namespace
}  // namespace rs
