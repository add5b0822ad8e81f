#include "rcdem/contact/local_point_records.hpp"

namespace rcdem {

void LocalPointRecords::init(const ContactNetwork& net) {
  const auto n = static_cast<std::size_t>(net.point_count());
  records.assign(n, LocalPointRecord{});
  for (std::size_t m = 0; m < n; ++m) {
    LocalPointRecord& r = records[m];
    const Vec3& p = net.point_position0[m];
    r.x0 = p.x();
    r.y0 = p.y();
    r.z0 = p.z();
    r.constants = net.constants[m];
  }
}

}  // namespace rcdem
