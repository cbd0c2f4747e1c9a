// Reader for gmsh's MSH 2.2 and 4.1 ASCII formats (gmsh reference manual, sec. "MSH file
// format" and "Legacy formats"). Only what a plane finite-element model needs is kept: node
// coordinates and the 2-D elements.
#include "meshfree/core/error.hpp"
#include "meshfree/fem/mesh.hpp"
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace mf::fem {

namespace {

/// Dimension and node count of the gmsh element types 1..31 (gmsh manual, "MSH file format",
/// elm-type list); dim -1 for types this table does not know.
struct GmshType {
  int dim;
  int nodes;
  const char* name;
};
GmshType gmsh_type(long t) {
  static const GmshType table[] = {
      {-1, 0, "unknown"},
      {1, 2, "2-node line"},
      {2, 3, "3-node triangle"},
      {2, 4, "4-node quadrangle"},
      {3, 4, "4-node tetrahedron"},
      {3, 8, "8-node hexahedron"},
      {3, 6, "6-node prism"},
      {3, 5, "5-node pyramid"},
      {1, 3, "3-node line"},
      {2, 6, "6-node triangle"},
      {2, 9, "9-node quadrangle"},
      {3, 10, "10-node tetrahedron"},
      {3, 27, "27-node hexahedron"},
      {3, 18, "18-node prism"},
      {3, 14, "14-node pyramid"},
      {0, 1, "point"},
      {2, 8, "8-node quadrangle"},
      {3, 20, "20-node hexahedron"},
      {3, 15, "15-node prism"},
      {3, 13, "13-node pyramid"},
      {2, 9, "9-node incomplete triangle"},
      {2, 10, "10-node triangle"},
      {2, 12, "12-node incomplete triangle"},
      {2, 15, "15-node triangle"},
      {2, 15, "15-node incomplete triangle"},
      {2, 21, "21-node triangle"},
      {1, 4, "4-node line"},
      {1, 5, "5-node line"},
      {1, 6, "6-node line"},
      {3, 20, "20-node tetrahedron"},
      {3, 35, "35-node tetrahedron"},
      {3, 56, "56-node tetrahedron"},
  };
  if (t < 1 || t >= static_cast<long>(sizeof(table) / sizeof(table[0]))) return table[0];
  return table[t];
}

/// The element types this code has (gmsh_element_type).
bool supported(long t, ElementType& type) {
  for (ElementType e : {ElementType::T3, ElementType::Q4, ElementType::Q8})
    if (t == gmsh_element_type(e)) {
      type = e;
      return true;
    }
  return false;
}

/// Whitespace-separated tokens with line numbers for the messages.
class Text {
public:
  Text(std::string path, std::string text) : path_(std::move(path)), s_(std::move(text)) {}

  template <class... Args> [[noreturn]] void error(const Args&... args) const {
    fail(path_, ":", line_, ": ", args...);
  }

  bool at_end() {
    skip_space();
    return pos_ >= s_.size();
  }
  /// The next token; `what` says what was expected if the file ends here.
  std::string_view token(const char* what) {
    skip_space();
    if (pos_ >= s_.size()) error("the file ends while reading ", what, "; it is cut short");
    const std::size_t b = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    return std::string_view(s_).substr(b, pos_ - b);
  }
  long long integer(const char* what) {
    const std::string t(token(what));
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (end != t.c_str() + t.size() || errno != 0)
      error("expected an integer (", what, "), got '", t, "'");
    return v;
  }
  double real(const char* what) {
    const std::string t(token(what));
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size() || errno != 0 || !std::isfinite(v))
      error("expected a number (", what, "), got '", t, "'");
    return v;
  }
  long long count(const char* what) {
    const long long n = integer(what);
    if (n < 0 || n > 2000000000LL) error("impossible ", what, ": ", n);
    return n;
  }
  /// The integers on the next non-empty line.
  void line_integers(const char* what, std::vector<long long>& out) {
    out.clear();
    skip_space();
    if (pos_ >= s_.size()) error("the file ends while reading ", what, "; it is cut short");
    while (pos_ < s_.size() && s_[pos_] != '\n') {
      if (is_space(s_[pos_])) {
        ++pos_;
        continue;
      }
      const std::size_t b = pos_;
      while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
      const std::string t = s_.substr(b, pos_ - b);
      char* end = nullptr;
      errno = 0;
      const long long v = std::strtoll(t.c_str(), &end, 10);
      if (end != t.c_str() + t.size() || errno != 0)
        error("expected an integer (", what, "), got '", t, "'");
      out.push_back(v);
    }
  }
  /// Reads up to and including the token `end` (skipping a section this reader does not use).
  void skip_to(const std::string& end, const std::string& section) {
    for (;;) {
      skip_space();
      if (pos_ >= s_.size()) error("the file ends inside ", section, " (no ", end, ")");
      if (token(end.c_str()) == end) return;
    }
  }
  void expect(std::string_view want) {
    const std::string_view got = token(std::string(want).c_str());
    if (got != want) error("expected ", want, ", got '", got, "'");
  }

private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string path_;
  std::string s_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

/// What the file holds, before unused nodes are dropped.
struct RawMesh {
  std::unordered_map<long long, int> node_of_tag;
  std::vector<Vec3> x;
  bool have_nodes = false, have_elements = false;
  bool have_type = false;
  ElementType type = ElementType::T3;
  long long first_tag = 0; // gmsh tag of the first 2-D element (for the mixed-type message)
  std::vector<long long> element_tag;
  std::vector<long long> node_tags; // nodes of the 2-D elements, by gmsh tag
};

void add_node(Text& in, RawMesh& raw, long long tag, const Vec3& p) {
  if (!raw.node_of_tag.emplace(tag, static_cast<int>(raw.x.size())).second)
    in.error("node ", tag, " is defined twice");
  raw.x.push_back(p);
}

/// One element line's type and nodes; keeps it if it is 2-D. `dim` is the entity dimension
/// (4.1) or -1 (2.2: taken from the type).
void add_element(Text& in, RawMesh& raw, long long tag, long type_id, int dim,
                 const long long* nodes, int count) {
  const GmshType g = gmsh_type(type_id);
  if (dim < 0) {
    if (g.dim < 0)
      in.error("element ", tag, " has gmsh type ", type_id,
               ", which this reader "
               "does not know");
    dim = g.dim;
  }
  if (g.dim >= 0 && count != g.nodes)
    in.error("element ", tag, " (", g.name, ") lists ", count, " nodes instead of ", g.nodes);
  if (dim < 2) return; // points and lines: boundary markers, not part of the body
  if (dim > 2)
    in.error("element ", tag, " is a 3-D element (", g.name,
             "); this reader takes plane meshes only");
  ElementType t;
  if (!supported(type_id, t))
    in.error("element ", tag, " has gmsh type ", type_id, " (", g.name,
             "); supported are 3-node triangles (2), 4-node quadrangles (3) and 8-node "
             "quadrangles (16)");
  if (!raw.have_type) {
    raw.have_type = true;
    raw.type = t;
    raw.first_tag = tag;
  } else if (t != raw.type) {
    in.error("the mesh mixes 2-D element types ", element_name(raw.type), " (element ",
             raw.first_tag, ") and ", element_name(t), " (element ", tag,
             "); one element type per mesh is supported");
  }
  raw.element_tag.push_back(tag);
  raw.node_tags.insert(raw.node_tags.end(), nodes, nodes + count);
}

void read_nodes_22(Text& in, RawMesh& raw) {
  const long long n = in.count("the number of nodes");
  raw.x.reserve(n);
  for (long long i = 0; i < n; ++i) {
    const long long tag = in.integer("a node tag");
    const double x = in.real("a node's x"), y = in.real("a node's y"), z = in.real("a node's z");
    add_node(in, raw, tag, {x, y, z});
  }
  in.expect("$EndNodes");
}

void read_elements_22(Text& in, RawMesh& raw) {
  const long long n = in.count("the number of elements");
  std::vector<long long> v;
  for (long long i = 0; i < n; ++i) {
    in.line_integers("an element line", v); // tag type ntags tags... nodes...
    if (v.size() < 3 || v[2] < 0 || static_cast<long long>(v.size()) < 3 + v[2])
      in.error("an element line needs a tag, a type, the number of tags and the tags");
    const int first = 3 + static_cast<int>(v[2]);
    add_element(in, raw, v[0], static_cast<long>(v[1]), -1, v.data() + first,
                static_cast<int>(v.size()) - first);
  }
  in.expect("$EndElements");
}

void read_nodes_41(Text& in, RawMesh& raw) {
  const long long blocks = in.count("the number of node blocks");
  const long long n = in.count("the number of nodes");
  in.integer("the smallest node tag");
  in.integer("the largest node tag");
  raw.x.reserve(n);
  std::vector<long long> tags;
  for (long long b = 0; b < blocks; ++b) {
    const long long dim = in.integer("a node block's entity dimension");
    in.integer("a node block's entity tag");
    const long long parametric = in.integer("whether a node block is parametric");
    const long long m = in.count("the number of nodes in a block");
    if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1))
      in.error("a node block has entity dimension ", dim, " and parametric flag ", parametric);
    tags.resize(m);
    for (auto& t : tags) t = in.integer("a node tag");
    for (long long k = 0; k < m; ++k) {
      const double x = in.real("a node's x"), y = in.real("a node's y"), z = in.real("a node's z");
      if (parametric)
        for (long long d = 0; d < dim; ++d) in.real("a node's parametric coordinate");
      add_node(in, raw, tags[k], {x, y, z});
    }
  }
  if (static_cast<long long>(raw.x.size()) != n)
    in.error("the $Nodes header announces ", n, " nodes, the blocks hold ", raw.x.size());
  in.expect("$EndNodes");
}

void read_elements_41(Text& in, RawMesh& raw) {
  const long long blocks = in.count("the number of element blocks");
  const long long n = in.count("the number of elements");
  in.integer("the smallest element tag");
  in.integer("the largest element tag");
  long long total = 0;
  std::vector<long long> v;
  for (long long b = 0; b < blocks; ++b) {
    const long long dim = in.integer("an element block's entity dimension");
    in.integer("an element block's entity tag");
    const long long type_id = in.integer("an element block's element type");
    const long long m = in.count("the number of elements in a block");
    if (dim < 0 || dim > 3) in.error("an element block has entity dimension ", dim);
    for (long long k = 0; k < m; ++k) {
      in.line_integers("an element line", v); // tag nodes...
      if (v.empty()) in.error("an empty element line");
      add_element(in, raw, v[0], static_cast<long>(type_id), static_cast<int>(dim), v.data() + 1,
                  static_cast<int>(v.size()) - 1);
    }
    total += m;
  }
  if (total != n)
    in.error("the $Elements header announces ", n, " elements, the blocks hold ", total);
  in.expect("$EndElements");
}

} // namespace

Mesh read_gmsh(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  MF_REQUIRE(file, path, ": cannot open the mesh file");
  std::ostringstream buffer;
  buffer << file.rdbuf();
  MF_REQUIRE(!file.bad(), path, ": reading the mesh file failed");
  Text in(path, buffer.str());

  if (in.at_end()) in.error("the file is empty");
  if (in.token("$MeshFormat") != "$MeshFormat")
    in.error("not a gmsh MSH file (it does not start with $MeshFormat)");
  const std::string version(in.token("the format version"));
  const long long file_type = in.integer("the file type");
  in.integer("the data size");
  if (file_type != 0)
    in.error("binary MSH files are not supported; write ASCII (gmsh -format msh22 or msh41 "
             "without -bin)");
  const bool v22 = version == "2.2", v41 = version == "4.1";
  if (!v22 && !v41)
    in.error("MSH version ", version,
             " is not supported; write version 2.2 or 4.1 (gmsh -format msh22 or msh41)");
  in.expect("$EndMeshFormat");

  RawMesh raw;
  while (!in.at_end()) {
    const std::string section(in.token("a section"));
    if (section.empty() || section[0] != '$') in.error("expected a section, got '", section, "'");
    const std::string name = section.substr(1);
    if (name == "Nodes") {
      if (raw.have_nodes) in.error("a second $Nodes section");
      v22 ? read_nodes_22(in, raw) : read_nodes_41(in, raw);
      raw.have_nodes = true;
    } else if (name == "Elements") {
      if (raw.have_elements) in.error("a second $Elements section");
      v22 ? read_elements_22(in, raw) : read_elements_41(in, raw);
      raw.have_elements = true;
    } else {
      in.skip_to("$End" + name, section);
    }
  }
  MF_REQUIRE(raw.have_nodes && raw.have_elements, path, ": no ",
             raw.have_nodes ? "$Elements" : "$Nodes", " section");
  MF_REQUIRE(raw.have_type, path, ": the file has no 2-D elements (triangles or quadrangles)");

  // Keep the nodes the elements use, in file order.
  Mesh mesh;
  mesh.type = raw.type;
  const int npe = nodes_per_element(raw.type);
  std::vector<int> new_index(raw.x.size(), -1);
  mesh.connectivity.resize(raw.node_tags.size());
  for (std::size_t k = 0; k < raw.node_tags.size(); ++k) {
    const auto it = raw.node_of_tag.find(raw.node_tags[k]);
    MF_REQUIRE(it != raw.node_of_tag.end(), path, ": element ", raw.element_tag[k / npe],
               " names node ", raw.node_tags[k], ", which is not in $Nodes");
    new_index[it->second] = 0;
    mesh.connectivity[k] = it->second;
  }
  std::vector<double> z;
  for (std::size_t i = 0; i < raw.x.size(); ++i)
    if (new_index[i] == 0) {
      new_index[i] = mesh.node_count();
      mesh.x.emplace_back(raw.x[i].x(), raw.x[i].y());
      z.push_back(raw.x[i].z());
    }
  for (int& c : mesh.connectivity) c = new_index[c];

  // A plane body: the nodes lie in one plane z = const (gmsh writes z = 0 for 2-D meshes).
  BoundingBox box{mesh.x[0], mesh.x[0]};
  for (const Vec2& p : mesh.x) box.lo = box.lo.cwiseMin(p), box.hi = box.hi.cwiseMax(p);
  const double tol = 1e-10 * std::max(box.size().maxCoeff(), 1e-300);
  for (std::size_t i = 0; i < z.size(); ++i)
    MF_REQUIRE(std::abs(z[i] - z[0]) <= tol, path,
               ": the nodes do not lie in one plane z = const (", z[0], " and ", z[i],
               "); this reader takes meshes in the x-y plane");

  orient_counter_clockwise(mesh, path);
  return mesh;
}

} // namespace mf::fem
