// A radio trace CSV (comm model `trace`; comm/radio_trace.hpp): parsed, checked against a team, looked up at
// every window's middle and written back and parsed again.
#include <sstream>

#include "../fuzz_target.hpp"
#include "cosmo/comm/radio_trace.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(radio_trace) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const comm::RadioTrace trace = comm::RadioTrace::parse(in, "input.csv");
  for (const comm::TraceWindow& w : trace.windows()) trace.find(w.robot_b, w.robot_a, w.start + w.duration / 2);
  std::ostringstream out;
  trace.write(out);
  std::istringstream again(out.str());
  comm::RadioTrace::parse(again, "written.csv");
  trace.checkTeam({'a', 'b', 'c', 'd'});
}
