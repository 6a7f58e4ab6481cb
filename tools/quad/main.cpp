// The `quad` command. The only translation unit that includes CLI11 (it costs ~9 s each).
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "topic_commands.hpp"

namespace {

void addConnectionOptions(CLI::App* command, quad::tools::ConnectionOptions& connection)
{
  command->add_option("--domain", connection.domain_id,
                      "DDS domain id (default: $QUAD_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"quad: run, inspect and test the quad flight stack"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "quad 0.1.0");

  auto* topic = app.add_subcommand("topic", "Inspect and publish topics of a running stack");
  topic->require_subcommand(1);

  quad::tools::TopicListOptions list_options;
  auto* list = topic->add_subcommand("list", "Topics seen on the domain, with writers and readers");
  addConnectionOptions(list, list_options.connection);
  list->add_option("--wait", list_options.wait_s, "Seconds to listen to discovery")
      ->check(CLI::Range(0.0, 60.0));
  list->add_flag("--contracts", list_options.contracts,
                 "Print quad's declared topics (name, type, QoS, rate, owner) instead");

  quad::tools::TopicEchoOptions echo_options;
  auto* echo = topic->add_subcommand("echo", "Print the samples of a topic, decoded from its IDL");
  addConnectionOptions(echo, echo_options.connection);
  echo->add_option("topic", echo_options.topic, "Topic name, e.g. quad/sim/state")->required();
  echo->add_option("-n,--count", echo_options.count, "Stop after N samples (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  echo->add_option("--timeout", echo_options.timeout_s,
                   "Exit 1 if --count samples did not arrive within this many seconds")
      ->check(CLI::NonNegativeNumber);
  echo->add_flag("--json", echo_options.json, "One JSON object per line");
  echo->add_option("--max-elements", echo_options.max_elements,
                   "Print at most this many elements of each list")
      ->check(CLI::PositiveNumber);

  quad::tools::TopicPubOptions pub_options;
  auto* pub = topic->add_subcommand("pub", "Publish samples given as YAML; the header is filled in");
  addConnectionOptions(pub, pub_options.connection);
  pub->add_option("topic", pub_options.topic, "Topic name, e.g. quad/system/command")->required();
  pub->add_option("values", pub_options.values,
                  "Fields as YAML, e.g. '{kind: COMMAND_TAKEOFF, altitude: 2}'")
      ->required();
  pub->add_option("-n,--count", pub_options.count, "How many samples")->check(CLI::PositiveNumber);
  pub->add_option("-r,--rate", pub_options.rate_hz, "Samples per second")->check(CLI::PositiveNumber);
  pub->add_option("--wait-match", pub_options.wait_match_s,
                  "Seconds to wait for a reader before the first sample")
      ->check(CLI::NonNegativeNumber);

  CLI11_PARSE(app, argc, argv);

  try {
    if (list->parsed()) {
      return quad::tools::topicList(list_options);
    }
    if (echo->parsed()) {
      return quad::tools::topicEcho(echo_options);
    }
    if (pub->parsed()) {
      return quad::tools::topicPub(pub_options);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quad: %s\n", e.what());
    return 1;
  }
  return 0;
}
