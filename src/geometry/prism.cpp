#include "meshfree/geometry/prism.hpp"
#include <algorithm>

namespace mf::geometry {

std::vector<std::string> Prism::face_names() const {
  std::vector<std::string> names;
  for (const Curve& c : section.boundary())
    if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
  names.push_back("back");
  names.push_back("front");
  return names;
}

} // namespace mf::geometry
