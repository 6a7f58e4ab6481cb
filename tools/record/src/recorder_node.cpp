// SPDX-License-Identifier: BSD-3-Clause
#include "quad/record/recorder_module.hpp"

#include <spdlog/spdlog.h>

#include "quad/bag/mcap.hpp"
#include "quad/common/param_table.hpp"
#include "quad/record/recorder.hpp"
#include "quad/runtime/lockstep.hpp"

namespace quad::record {

namespace {

/// [ns] of wall time between takes: a round's samples gather meanwhile, taken with one
/// wake-up of the recorder's thread, as quad record's are.
constexpr std::int64_t kTakePeriodNs = 10'000'000;

const common::ParamTable<RecordOptions>& recorderTable()
{
  static const common::ParamTable<RecordOptions> table = [] {
    common::ParamTable<RecordOptions> t;
    t.text("output", [](RecordOptions& o) -> std::string& { return o.output; }, {},
           "the MCAP file recorded to (required)")
        .list("topics", [](RecordOptions& o) -> std::vector<std::string>& { return o.topics; },
              "topics (names or globs) recorded; empty: every quad topic")
        .list("exclude", [](RecordOptions& o) -> std::vector<std::string>& { return o.exclude; },
              "topics (globs) left out");
    return t;
  }();
  return table;
}

RecordOptions recorderOptionsFrom(const common::Params& p)
{
  RecordOptions options = recorderTable().read(p);
  if (options.output.empty()) {
    throw common::ConfigError({common::configProblem(p.origin(), "output", options.output,
                                                     "a hosted recorder needs the file it records to")});
  }
  options.quiet = true;  // a container's log has no progress line
  return options;
}

/// The recorder on a container's participant: takes what its readers hold every
/// kTakePeriodNs, and closes the recording when the container stops.
class RecorderNode final : public runtime::Node {
public:
  RecorderNode(const RecordOptions& options, dds::Participant participant)
      : Node(runtime::kRecorderParticipant, std::move(participant)), recorder_(this->participant(), options, nullptr)
  {
    setTickPeriod(kTakePeriodNs);
  }

protected:
  void onTick(std::int64_t /*steady_ns*/) override
  {
    try {
      recorder_.poll();
    } catch (const bag::BagError& e) {
      // The modules beside it fly on; the recording stops here, as quad record's would.
      counters().errors++;
      spdlog::error("record: {}: the recording stops", e.what());
    }
  }
  void onStop() override
  {
    if (!recorder_.finish()) {
      counters().errors++;
    }
  }

private:
  Recorder recorder_;
};

}  // namespace

runtime::ModuleEntry recorderModule()
{
  common::ParamSchema schema = recorderTable().schema();
  return {runtime::kRecorderParticipant, schema,
          [](const common::Params& params, dds::Participant participant) -> std::unique_ptr<runtime::Node> {
            return std::make_unique<RecorderNode>(recorderOptionsFrom(params), std::move(participant));
          },
          true};
}

}  // namespace quad::record
