#include "run/field_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iterator>

namespace nsb {

namespace {

constexpr int kVtkVertex = 1, kVtkLine = 3, kVtkQuad = 9, kVtkHexahedron = 12;

void open_array(std::string& out, const char* type, const std::string& name, int components) {
  fmt::format_to(std::back_inserter(out), "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                 type, name, components);
}

int vtk_type(int points) {
  return points == 1 ? kVtkVertex : points == 2 ? kVtkLine : points == 4 ? kVtkQuad : kVtkHexahedron;
}

// The columns of FieldMesh::points: (x, y) in 1D and 2D, (x, y, z) in 3D.
Index point_columns(int dimension) { return dimension == 3 ? 3 : 2; }

}  // namespace

void check_field_mesh(const FieldMesh& m, const Problem& p, const std::string& context) {
  const auto fail = [&](const std::string& why) {
    throw InputError(fmt::format("{}: problem {}: field_mesh(): {}", context, p.name(), why));
  };
  if (m.dimension < 1 || m.dimension > 3) fail(fmt::format("dimension {}; valid: 1, 2 or 3", m.dimension));
  if (m.points.cols() != point_columns(m.dimension) || m.point_dofs.rows() != m.npoints() || m.point_dofs.cols() != m.dimension)
    fail("points must be npoints x 2 (x 3 in 3D) and point_dofs npoints x dimension");
  if (m.point_dofs.size() > 0 && (m.point_dofs.minCoeff() < -1 || m.point_dofs.maxCoeff() >= p.ndof()))
    fail(fmt::format("a point dof outside [-1, ndof = {})", p.ndof()));
  if (m.cell_body.size() != static_cast<std::size_t>(m.ncells())) fail("cell_body needs one entry per cell");
  for (Index c = 0; c < m.ncells(); ++c) {
    const int n = m.cell_size(c);
    if (n != 1 && n != 2 && n != 4 && n != 8) fail(fmt::format("cell {} has {} points; valid: 1, 2, 4 or 8", c, n));
    for (Index k = 0; k < m.cells.cols(); ++k)
      if (const int a = m.cells(c, k); k < n ? a >= m.npoints() : a != -1)
        fail(fmt::format("cell {}: point {} outside [0, {}) or not padded with -1", c, a, m.npoints()));
  }
  if (m.nelements() > 0 && m.stress_components.empty()) fail("element cells and no stress component");
  for (const FieldArray& a : m.body_arrays)
    if (a.components != 1 && a.components != 3)
      fail(fmt::format("body array {}: {} components; valid: 1 or 3", a.name, a.components));
  if (!m.body_rotation_dofs.empty()) {
    if (m.dimension != 3 || m.body_rotation_dofs.size() != static_cast<std::size_t>(m.nbodies()))
      fail(fmt::format("body_rotation_dofs: {} entries; valid: none, or one per body cell ({}) of a 3D mesh",
                       m.body_rotation_dofs.size(), m.nbodies()));
    for (const int r : m.body_rotation_dofs)
      if (r < -1 || r + 3 > p.ndof()) fail(fmt::format("body_rotation_dofs: {} outside -1 or [0, ndof - 3 = {}]", r, p.ndof() - 3));
  }
}

FieldWriter::Part FieldWriter::make_part(bool elements) const {
  Part part;
  part.name = elements ? "fields_" : "bodies_";
  part.elements = elements;
  // Local point numbers: elements' points in the mesh's order (a mesh of elements only is
  // written as it is); a point per vertex cell in the cells' order (the rows of body_data()).
  std::vector<Index> local(static_cast<std::size_t>(mesh_.npoints()), -1);
  for (Index c = 0; c < mesh_.ncells(); ++c) {
    if ((mesh_.cell_size(c) >= 2) != elements) continue;
    part.cells.push_back(c);
    if (elements)
      for (Index k = 0; k < mesh_.cell_size(c); ++k) local[static_cast<std::size_t>(mesh_.cells(c, k))] = 0;
  }
  if (elements) {
    for (Index a = 0; a < mesh_.npoints(); ++a)
      if (local[static_cast<std::size_t>(a)] == 0) {
        local[static_cast<std::size_t>(a)] = static_cast<Index>(part.points.size());
        part.points.push_back(a);
      }
  } else {
    for (const Index c : part.cells) part.points.push_back(mesh_.cells(c, 0));
  }
  const auto np = part.points.size(), nc = part.cells.size();
  auto out = std::back_inserter(part.head);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
                 "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n",
                 np, nc);
  open_array(part.head, "Float64", "reference_position", 3);
  for (const Index a : part.points)
    fmt::format_to(out, "{} {} {}\n", mesh_.points(a, 0), mesh_.points(a, 1), mesh_.dimension == 3 ? mesh_.points(a, 2) : 0.0);
  part.head += "</DataArray>\n</Points>\n<Cells>\n";
  open_array(part.head, "Int64", "connectivity", 1);
  for (std::size_t j = 0; j < nc; ++j) {
    const Index c = part.cells[j];
    for (Index k = 0; k < mesh_.cell_size(c); ++k)
      fmt::format_to(out, "{} ", elements ? local[static_cast<std::size_t>(mesh_.cells(c, k))] : static_cast<Index>(j));
    part.head.back() = '\n';
  }
  part.head += "</DataArray>\n";
  open_array(part.head, "Int64", "offsets", 1);
  Index offset = 0;
  for (const Index c : part.cells) fmt::format_to(out, "{}\n", offset += mesh_.cell_size(c));
  part.head += "</DataArray>\n";
  open_array(part.head, "UInt8", "types", 1);
  for (const Index c : part.cells) fmt::format_to(out, "{}\n", vtk_type(mesh_.cell_size(c)));
  part.head += "</DataArray>\n</Cells>\n";
  open_array(part.tail, "Int32", "body", 1);
  for (const Index c : part.cells)
    fmt::format_to(std::back_inserter(part.tail), "{}\n", mesh_.cell_body[static_cast<std::size_t>(c)]);
  part.tail += "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return part;
}

FieldWriter::FieldWriter(const Problem& problem, const std::filesystem::path& dir, const std::string& option,
                         long expected_writes)
    : problem_(problem),
      mesh_([&] {
        auto mesh = problem.field_mesh();
        if (!mesh)
          throw InputError(fmt::format("{}: problem {} describes no bodies to write (Problem::field_mesh())", option,
                                       problem.name()));
        check_field_mesh(*mesh, problem, option);
        return std::move(*mesh);
      }()),
      dir_(dir, option) {
  namespace fs = std::filesystem;
  // The staging holds links to the directory's files: an earlier run's fields are not ours.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_.path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name == "fields.pvd" || ((name.starts_with("fields_") || name.starts_with("bodies_")) && name.ends_with(".vtu")))
      fs::remove(e.path(), ec);
  }
  if (mesh_.nelements() > 0) parts_.push_back(make_part(true));
  if (mesh_.nbodies() > 0) parts_.push_back(make_part(false));
  stress_.resize(mesh_.nelements(), static_cast<Index>(mesh_.stress_components.size()));
  body_.resize(mesh_.nbodies(), mesh_.body_columns());
  impulse_.resize(problem.ndof());
  if (problem.contacts_move()) moving_ = problem.contact_geometry();
  orientation_.assign(mesh_.body_rotation_dofs.size(), Eigen::Quaterniond::Identity());
  rotation_seen_ = Vec::Zero(3 * static_cast<Index>(mesh_.body_rotation_dofs.size()));
  // At most 25 characters a number (shortest round-trip form, and a separator): 9 per point
  // (three vectors) and the body arrays, one per cell and component. No write grows the
  // buffer again.
  std::size_t largest = 0;
  for (const Part& part : parts_)
    largest = std::max(largest, part.head.size() + part.tail.size() +
                                    25 * (9 * part.points.size() + static_cast<std::size_t>(stress_.size() + body_.size()) +
                                          6 * orientation_.size()));
  buffer_.reserve(largest + 4096);
  prefix_ = dir_.path().string() + "/";
  path_.reserve(prefix_.size() + 32);
  times_.reserve(static_cast<std::size_t>(std::clamp(expected_writes, 1L, 1L << 16)));  // grows past that
}

void FieldWriter::append_point_vector(const char* name, const Part& part, const Vec& dof_values) {
  open_array(buffer_, "Float64", name, 3);
  auto out = std::back_inserter(buffer_);
  for (const Index a : part.points) {
    double x[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < mesh_.dimension; ++k)
      if (const int d = mesh_.point_dofs(a, k); d >= 0) x[k] = dof_values[d];
    fmt::format_to(out, "{} {} {}\n", x[0], x[1], x[2]);
  }
  buffer_ += "</DataArray>\n";
}

void FieldWriter::follow(const State& s) {
  for (std::size_t b = 0; b < orientation_.size(); ++b) {
    const int r = mesh_.body_rotation_dofs[b];
    if (r < 0) continue;
    auto seen = rotation_seen_.segment<3>(3 * static_cast<Index>(b));
    const Eigen::Vector3d turn = s.u.segment<3>(r) - seen;  // this step's rotation vector (0 at the first state)
    seen = s.u.segment<3>(r);
    if (!followed_) continue;
    if (const double angle = turn.norm(); angle > 0.0)
      orientation_[b] = (Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle)) * orientation_[b]).normalized();
  }
  followed_ = true;
}

void FieldWriter::append_orientations() {
  auto out = std::back_inserter(buffer_);
  for (int axis : {0, 2}) {
    open_array(buffer_, "Float64", axis == 0 ? "orientation_x" : "orientation_z", 3);
    for (const Eigen::Quaterniond& q : orientation_) {
      const Eigen::Vector3d e = q * Eigen::Vector3d::Unit(axis);
      fmt::format_to(out, "{} {} {}\n", e[0], e[1], e[2]);
    }
    buffer_ += "</DataArray>\n";
  }
}

void FieldWriter::state(const State& s, const Vec& normal_impulses, const Vec& tangential_impulses,
                        const Vec& tangential_impulses2) {
  follow(s);
  const Contacts& c = problem_.contacts();
  if (problem_.contacts_move()) {
    // The rows at s.u, along which the impulses acted (schemes state their configuration).
    problem_.evaluate_contacts(s.u, moving_);
    impulse_.noalias() = moving_.normal.transpose() * normal_impulses;
    if (moving_.tangent.rows() > 0 && tangential_impulses.size() == moving_.tangent.rows())
      impulse_.noalias() += moving_.tangent.transpose() * tangential_impulses;
    if (moving_.tangent2.rows() > 0 && tangential_impulses2.size() == moving_.tangent2.rows())
      impulse_.noalias() += moving_.tangent2.transpose() * tangential_impulses2;
  } else {
    impulse_.noalias() = c.normal.transpose() * normal_impulses;
    if (c.tangent.rows() > 0 && tangential_impulses.size() == c.tangent.rows())
      impulse_.noalias() += c.tangent.transpose() * tangential_impulses;
    if (c.tangent2.rows() > 0 && tangential_impulses2.size() == c.tangent2.rows())
      impulse_.noalias() += c.tangent2.transpose() * tangential_impulses2;
  }
  if (stress_.rows() > 0) problem_.cell_stress(s.u, stress_);
  if (body_.size() > 0) problem_.body_data(s, body_);

  for (const Part& part : parts_) {
    const bool elements = part.elements;
    auto out = std::back_inserter(buffer_);
    buffer_.assign(part.head);
    buffer_ += "<PointData Vectors=\"displacement\">\n";
    append_point_vector("displacement", part, s.u);
    append_point_vector("velocity", part, s.v);
    append_point_vector("contact_impulse", part, impulse_);
    if (!elements) {
      // One point per body cell, in their order: the rows of body_.
      Index column = 0;
      for (const FieldArray& a : mesh_.body_arrays) {
        open_array(buffer_, "Float64", a.name, a.components);
        for (Index b = 0; b < body_.rows(); ++b) {
          for (Index k = 0; k < a.components; ++k) fmt::format_to(out, "{} ", body_(b, column + k));
          buffer_.back() = '\n';
        }
        buffer_ += "</DataArray>\n";
        column += a.components;
      }
      if (!orientation_.empty()) append_orientations();
    }
    buffer_ += "</PointData>\n";
    if (elements && !mesh_.stress_components.empty()) {
      fmt::format_to(out, "<CellData Scalars=\"{}\">\n", mesh_.stress_components[0]);
      for (Index k = 0; k < stress_.cols(); ++k) {
        open_array(buffer_, "Float64", mesh_.stress_components[static_cast<std::size_t>(k)], 1);
        for (Index e = 0; e < stress_.rows(); ++e) fmt::format_to(out, "{}\n", stress_(e, k));
        buffer_ += "</DataArray>\n";
      }
    } else {
      buffer_ += "<CellData>\n";
    }
    buffer_ += part.tail;

    path_.assign(prefix_);  // within its reserved capacity: no new string per file
    fmt::format_to(std::back_inserter(path_), "{}{:06d}.vtu", part.name, times_.size());
    flush(path_);
  }
  times_.push_back(s.t);
}

// POSIX I/O, not stdio: fopen allocates its FILE and buffer, and the buffer is whole here.
void FieldWriter::flush(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  std::size_t done = 0;
  while (fd >= 0 && done < buffer_.size()) {
    const ssize_t n = ::write(fd, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  const int err = errno;
  const bool closed = fd >= 0 && ::close(fd) == 0;
  if (done < buffer_.size() || !closed)
    throw InputError(fmt::format("cannot write '{}': {}", path, std::strerror(done < buffer_.size() ? err : errno)));
}

void FieldWriter::commit() {
  buffer_ = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n";
  for (std::size_t i = 0; i < times_.size(); ++i)
    for (std::size_t j = 0; j < parts_.size(); ++j)
      fmt::format_to(std::back_inserter(buffer_), "<DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}{:06d}.vtu\"/>\n",
                     times_[i], j, parts_[j].name, i);
  buffer_ += "</Collection>\n</VTKFile>\n";
  flush((dir_.path() / "fields.pvd").string());
  dir_.commit();
}

}  // namespace nsb
