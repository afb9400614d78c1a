#include "lift/format_point.h"

#include <sstream>

namespace liftmap {

std::string format_point(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

}  // namespace liftmap
