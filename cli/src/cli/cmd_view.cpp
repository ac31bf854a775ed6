// rollsense view DATASET: the live view's page over a recorded dataset (a
// trial browser), until Ctrl-C or --for S seconds.
#include <csignal>
#include <cstdio>
#include <ctime>
#include <memory>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "live/http_server.hpp"
#include "live/live_view.hpp"
#include "live/site.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/log.hpp"

namespace rollsense::cli {
namespace {

const char* kHelp = R"(usage: rollsense view DATASET [options]

Serve the live view's page over a recorded dataset: the list of its trials,
and each trial's sensor channels and recorded joints against time (the trial
shown before it faded behind). The same page as 'rollsense run --live';
read-only, and only the dataset's trials are served (looked up by id in its
manifest). Serves until Ctrl-C.

options:
  --port N          port to listen on (default 8027; 0: any free port, printed)
  --bind ADDR       listen on ADDR instead of 127.0.0.1 (warns)
  --for S           stop after S seconds (scripts, tests)
  -v, --verbose     debug messages;   -q, --quiet   no info messages: warnings, errors
                    and the address to open

exit codes: 0 ok, 2 bad command line, 3 DATASET cannot be read,
            5 the port cannot be listened on)";

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    args.reject_unknown({"--port", "--bind", "--for", "-v", "--verbose", "-q", "--quiet"});
    auto pos = args.positionals({"--port", "--bind", "--for"});
    if (pos.size() != 1) throw UsageError("expects one DATASET (see --help)");
    setup_logging(args);
    const auto port = static_cast<std::uint16_t>(args.unsigned_option("--port", live::kDefaultPort, 0, 65535));
    const double seconds = args.number_option("--for", 0, 0, 1e9);
    std::string address = "127.0.0.1";
    if (auto bind = args.option("--bind"); !bind.empty()) {
        if (auto s = live::HttpServer::check_address(bind); !s.ok()) throw UsageError("--bind: " + s.message());
        address = bind;
        if (bind != "127.0.0.1" && bind != "::1")
            log_warning("rollsense", "--bind " + bind + ": the dataset can be browsed from other machines");
    }
    auto dataset = DatasetReader::open(pos[0]);
    if (!dataset) throw StatusError(Status{dataset.error()});
    auto shared = std::make_shared<const DatasetReader>(std::move(*dataset));

    // Ctrl-C and SIGTERM end the view: waited for here, not handled.
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop, nullptr);  // before the server's threads start: they inherit it
    auto server = live::HttpServer::start(address, port, live::dataset_site(shared), nullptr,
                                          "--port N, or --port 0 for any free one");
    if (!server) throw StatusError(Status{server.error()});
    std::fprintf(stderr, "viewing %s (%zu trials): %s  (Ctrl-C ends)\n", pos[0].c_str(), shared->trials().size(),
                 (*server)->where().c_str());
    if (seconds > 0) {
        const timespec wait{static_cast<time_t>(seconds), static_cast<long>((seconds - static_cast<double>(
                                                                                 static_cast<time_t>(seconds))) * 1e9)};
        sigtimedwait(&stop, nullptr, &wait);
    } else {
        int sig = 0;
        sigwait(&stop, &sig);
    }
    return kExitOk;
}

const Registration reg{{"view", "browse a recorded dataset in the live view's page", kHelp, &run}};

}  // namespace
}  // namespace rollsense::cli
