#pragma once
// A comm model as every driver names it (cosmo_generate --comm, the comm_broker's ~comm / ~config, comm_simulate
// --comm, the suite's comm models), resolved here, once:
//   a name    wifi or proradio (pro-radio, pro_radio are proradio): <config_dir>/comm/<name>.yaml when that file
//             exists, else the built-in model (RadioParams::byName);
//   a .yaml   that file (RadioParams::fromConfig);
//   a .csv    a radio trace (radio_trace.hpp) replayed inside its windows, Wi-Fi's phi(d) (the name wifi as above)
//             outside them.
#include <string>

#include "cosmo/comm/radio_params.hpp"

namespace cosmo::comm {

struct CommModel {
  std::string label;  ///< what the dataset's name says: the name (proradio for its spellings) or the file's stem
  std::string file;   ///< the model file read ("": built in)
  std::string trace;  ///< the radio trace replayed ("": none)
  RadioParams params;
};

/// `config_dir` empty: names are the built-in models. Throws std::runtime_error naming what it cannot read or know.
CommModel resolveCommModel(const std::string& comm, const std::string& config_dir);

}  // namespace cosmo::comm
