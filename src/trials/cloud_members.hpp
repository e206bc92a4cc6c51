#pragma once
// The PointCloud2 members after its header, in the order ROS 1 and CDR both serialize them: height, width, fields
// (uint32 count; per field name, uint32 offset, uint8 datatype, uint32 count), uint8 is_bigendian, point_step,
// row_step, uint8[] data, uint8 is_dense. `In` reads one member at a time, in its serialization's rules:
// in.template value<T>(what), in.string(what), in.bytes(n, what).
#include <cstdint>

#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

/// Reads them into `view`; `check_fields(n)` throws when `n` fields cannot fit in what is left.
template <typename In, typename CheckFields>
void readCloudMembers(In& in, CloudView& view, const CheckFields& check_fields) {
  CloudLayout& L = view.layout;
  L.height = in.template value<std::uint32_t>("height");
  L.width = in.template value<std::uint32_t>("width");
  const auto nfields = in.template value<std::uint32_t>("fields");
  check_fields(nfields);
  L.fields.resize(nfields);
  for (auto& f : L.fields) {
    f.name = in.string("fields[].name");
    f.offset = in.template value<std::uint32_t>("fields[].offset");
    f.datatype = in.template value<std::uint8_t>("fields[].datatype");
    f.count = in.template value<std::uint32_t>("fields[].count");
  }
  L.is_bigendian = in.template value<std::uint8_t>("is_bigendian") != 0;
  L.point_step = in.template value<std::uint32_t>("point_step");
  L.row_step = in.template value<std::uint32_t>("row_step");
  view.bytes = in.template value<std::uint32_t>("data");
  view.data = in.bytes(view.bytes, "data");
  L.is_dense = in.template value<std::uint8_t>("is_dense") != 0;
}

}  // namespace cosmo::trials
