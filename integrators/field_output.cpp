#include "integrators/field_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iterator>

namespace nsb {

namespace {

constexpr int kVtkLine = 3, kVtkQuad = 9;

void open_array(std::string& out, const char* type, const std::string& name, int components) {
  fmt::format_to(std::back_inserter(out), "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                 type, name, components);
}

}  // namespace

FieldWriter::FieldWriter(const Problem& problem, const std::filesystem::path& dir, const std::string& option,
                         long expected_writes)
    : problem_(problem),
      mesh_([&] {
        auto mesh = problem.field_mesh();
        if (!mesh)
          throw InputError(fmt::format("{}: problem {} has no body mesh to write (field output is for problems built "
                                       "from bars or plane bodies)",
                                       option, problem.name()));
        return std::move(*mesh);
      }()),
      dir_(dir, option) {
  namespace fs = std::filesystem;
  // The staging holds links to the directory's files: an earlier run's fields are not ours.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_.path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name == "fields.pvd" || (name.starts_with("fields_") && name.ends_with(".vtu"))) fs::remove(e.path(), ec);
  }
  const Index np = mesh_.npoints(), nc = mesh_.ncells();
  auto out = std::back_inserter(head_);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
                 "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n",
                 np, nc);
  open_array(head_, "Float64", "reference_position", 3);
  for (Index a = 0; a < np; ++a) fmt::format_to(out, "{} {} 0\n", mesh_.points(a, 0), mesh_.points(a, 1));
  head_ += "</DataArray>\n</Points>\n<Cells>\n";
  open_array(head_, "Int64", "connectivity", 1);
  for (Index c = 0; c < nc; ++c) {
    for (Index k = 0; k < mesh_.cells.cols(); ++k) fmt::format_to(out, "{} ", mesh_.cells(c, k));
    head_.back() = '\n';
  }
  head_ += "</DataArray>\n";
  open_array(head_, "Int64", "offsets", 1);
  for (Index c = 0; c < nc; ++c) fmt::format_to(out, "{}\n", (c + 1) * mesh_.cells.cols());
  head_ += "</DataArray>\n";
  open_array(head_, "UInt8", "types", 1);
  const int type = mesh_.cells.cols() == 2 ? kVtkLine : kVtkQuad;
  for (Index c = 0; c < nc; ++c) fmt::format_to(out, "{}\n", type);
  head_ += "</DataArray>\n</Cells>\n";
  open_array(tail_, "Int32", "body", 1);
  for (const int b : mesh_.cell_body) fmt::format_to(std::back_inserter(tail_), "{}\n", b);
  tail_ += "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";

  stress_.resize(nc, static_cast<Index>(mesh_.stress_components.size()));
  impulse_.resize(problem.ndof());
  // At most 25 characters a number (shortest round-trip form, and a separator): 9 per point
  // (three vectors), one per cell and component. No write grows the buffer again.
  buffer_.reserve(head_.size() + tail_.size() + static_cast<std::size_t>(25 * (9 * np + stress_.size()) + 4096));
  prefix_ = (dir_.path() / "fields_").string();
  path_.reserve(prefix_.size() + 32);
  times_.reserve(static_cast<std::size_t>(std::clamp(expected_writes, 1L, 1L << 16)));  // grows past that
}

void FieldWriter::append_point_vector(const char* name, const Vec& dof_values) {
  open_array(buffer_, "Float64", name, 3);
  auto out = std::back_inserter(buffer_);
  for (Index a = 0; a < mesh_.npoints(); ++a) {
    double x[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < mesh_.dimension; ++k)
      if (const int d = mesh_.point_dofs(a, k); d >= 0) x[k] = dof_values[d];
    fmt::format_to(out, "{} {} {}\n", x[0], x[1], x[2]);
  }
  buffer_ += "</DataArray>\n";
}

void FieldWriter::state(const State& s, const Vec& normal_impulses, const Vec& tangential_impulses) {
  const Contacts& c = problem_.contacts();
  impulse_.noalias() = c.normal.transpose() * normal_impulses;
  if (c.tangent.rows() > 0 && tangential_impulses.size() == c.tangent.rows())
    impulse_.noalias() += c.tangent.transpose() * tangential_impulses;
  problem_.cell_stress(s.u, stress_);

  buffer_.assign(head_);
  buffer_ += "<PointData Vectors=\"displacement\">\n";
  append_point_vector("displacement", s.u);
  append_point_vector("velocity", s.v);
  append_point_vector("contact_impulse", impulse_);
  buffer_ += "</PointData>\n";
  fmt::format_to(std::back_inserter(buffer_), "<CellData Scalars=\"{}\">\n", mesh_.stress_components[0]);
  for (Index k = 0; k < stress_.cols(); ++k) {
    open_array(buffer_, "Float64", mesh_.stress_components[static_cast<std::size_t>(k)], 1);
    for (Index e = 0; e < stress_.rows(); ++e) fmt::format_to(std::back_inserter(buffer_), "{}\n", stress_(e, k));
    buffer_ += "</DataArray>\n";
  }
  buffer_ += tail_;

  path_.assign(prefix_);  // within its reserved capacity: no new string per file
  fmt::format_to(std::back_inserter(path_), "{:06d}.vtu", times_.size());
  flush(path_);
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
    fmt::format_to(std::back_inserter(buffer_), "<DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"fields_{:06d}.vtu\"/>\n",
                   times_[i], i);
  buffer_ += "</Collection>\n</VTKFile>\n";
  flush((dir_.path() / "fields.pvd").string());
  dir_.commit();
}

}  // namespace nsb
