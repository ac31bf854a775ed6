// What the live view serves, and nothing else: GET (or HEAD) of the page and
// its assets, info.json, and either the run's event stream (live) or a
// recorded dataset's trials by id (view: no file paths reach the server, so
// nothing outside the dataset can be asked for). Other paths get 404, other
// methods 405: the page cannot start, stop or change anything.
#pragma once

#include <memory>
#include <string>

#include "live/http_server.hpp"
#include "rollsense/dataset.hpp"

namespace rollsense::live {

// `rollsense run --live`: the page and /events.
Site live_site(std::string script, std::string profile);
// `rollsense view DATASET`: the page and the dataset's trials.
Site dataset_site(std::shared_ptr<const DatasetReader> dataset);

}  // namespace rollsense::live
