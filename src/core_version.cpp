// cosmo_core: the union of the core module libraries (see CMakeLists.txt).
namespace cosmo {
const char* version() { return "0.1.0"; }
}  // namespace cosmo
