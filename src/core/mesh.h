#pragma once
/// The one connectivity structure of liftmap: a halfedge mesh of a manifold, consistently oriented triangle
/// surface, closed or with boundary. Built once from a face list; geometry (positions, flattenings) is kept
/// outside, as #V by k Eigen matrices indexed by vertex id, so the same connectivity serves the surface in
/// R^3 and its flattenings.

#include <Eigen/Core>
#include <array>
#include <compare>
#include <cstdint>
#include <vector>

namespace liftmap {

/// A typed index into one kind of mesh element. `idx < 0` means "none".
template <class Tag>
struct Handle {
  int idx = -1;
  constexpr Handle() = default;
  constexpr explicit Handle(int i) : idx(i) {}
  [[nodiscard]] constexpr bool valid() const { return idx >= 0; }
  constexpr auto operator<=>(const Handle&) const = default;
};

struct VertexTag {};
struct FaceTag {};
struct EdgeTag {};
struct HalfedgeTag {};
using VertexId = Handle<VertexTag>;
using FaceId = Handle<FaceTag>;
using EdgeId = Handle<EdgeTag>;
using HalfedgeId = Handle<HalfedgeTag>;

/// Per-element data: a vector indexed by a typed handle.
template <class H, class T>
class ElementData {
 public:
  ElementData() = default;
  explicit ElementData(int n, const T& value = T()) : data_(static_cast<size_t>(n), value) {}
  typename std::vector<T>::reference operator[](H h) { return data_[static_cast<size_t>(h.idx)]; }
  typename std::vector<T>::const_reference operator[](H h) const { return data_[static_cast<size_t>(h.idx)]; }
  [[nodiscard]] int size() const { return static_cast<int>(data_.size()); }
  void resize(int n, const T& value = T()) { data_.resize(static_cast<size_t>(n), value); }
  std::vector<T>& raw() { return data_; }
  [[nodiscard]] const std::vector<T>& raw() const { return data_; }

 private:
  std::vector<T> data_;
};
template <class T>
using VertexData = ElementData<VertexId, T>;
template <class T>
using FaceData = ElementData<FaceId, T>;
template <class T>
using EdgeData = ElementData<EdgeId, T>;
template <class T>
using HalfedgeData = ElementData<HalfedgeId, T>;

/// Halfedge connectivity. Edge `e` owns halfedges `2e` and `2e+1` (twins). Each face's first halfedge runs
/// from its first to its second vertex in input order, so `face_vertices(f)` returns the input order. Boundary
/// halfedges have no face and are linked by next/prev into boundary loops.
class Mesh {
 public:
  Mesh() = default;

  /// Builds the connectivity.
  /// \param F #F by 3 vertex indices, counter-clockwise seen from outside.
  /// \param n_vertices number of vertices (>= max index + 1; vertices referenced by no face are allowed and
  ///        stay isolated).
  /// \throw InvalidInputError naming the element if an index is out of range, a face repeats a vertex, an edge
  ///        has more than two faces, two faces disagree on orientation, or a vertex is non-manifold.
  Mesh(const Eigen::MatrixXi& F, int n_vertices);

  [[nodiscard]] int n_vertices() const { return static_cast<int>(v_halfedge_.size()); }
  [[nodiscard]] int n_faces() const { return static_cast<int>(f_halfedge_.size()); }
  [[nodiscard]] int n_edges() const { return static_cast<int>(he_next_.size() / 2); }
  [[nodiscard]] int n_halfedges() const { return static_cast<int>(he_next_.size()); }

  [[nodiscard]] HalfedgeId next(HalfedgeId h) const { return he_next_[h.idx]; }
  [[nodiscard]] HalfedgeId prev(HalfedgeId h) const { return he_prev_[h.idx]; }
  [[nodiscard]] static HalfedgeId twin(HalfedgeId h) { return HalfedgeId(h.idx ^ 1); }
  [[nodiscard]] VertexId tail(HalfedgeId h) const { return he_tail_[h.idx]; }
  [[nodiscard]] VertexId head(HalfedgeId h) const { return he_tail_[h.idx ^ 1]; }
  /// The face left of `h`; invalid for a boundary halfedge.
  [[nodiscard]] FaceId face(HalfedgeId h) const { return he_face_[h.idx]; }
  [[nodiscard]] static EdgeId edge(HalfedgeId h) { return EdgeId(h.idx >> 1); }
  [[nodiscard]] static HalfedgeId halfedge(EdgeId e) { return HalfedgeId(2 * e.idx); }
  [[nodiscard]] HalfedgeId halfedge(FaceId f) const { return f_halfedge_[f.idx]; }
  /// An outgoing halfedge of `v`: for a boundary vertex the one whose twin is a boundary halfedge, so that
  /// `outgoing(v)` walks the whole fan. Invalid for an isolated vertex.
  [[nodiscard]] HalfedgeId halfedge(VertexId v) const { return v_halfedge_[v.idx]; }

  [[nodiscard]] bool is_boundary(HalfedgeId h) const { return !he_face_[h.idx].valid(); }
  [[nodiscard]] bool is_boundary(EdgeId e) const { return is_boundary(halfedge(e)) || is_boundary(twin(halfedge(e))); }
  [[nodiscard]] bool is_boundary(VertexId v) const {
    const HalfedgeId h = halfedge(v);
    return h.valid() && is_boundary(twin(h));
  }
  [[nodiscard]] bool is_isolated(VertexId v) const { return !halfedge(v).valid(); }

  /// The three vertices of `f` in input order.
  [[nodiscard]] std::array<VertexId, 3> face_vertices(FaceId f) const {
    const HalfedgeId h = halfedge(f);
    return {tail(h), tail(next(h)), tail(prev(h))};
  }
  /// The three halfedges of `f`; halfedge i runs from vertex i to vertex i+1 (mod 3) of `face_vertices(f)`.
  [[nodiscard]] std::array<HalfedgeId, 3> face_halfedges(FaceId f) const {
    const HalfedgeId h = halfedge(f);
    return {h, next(h), prev(h)};
  }

  /// Next outgoing halfedge of the same vertex, counter-clockwise (across the face left of `h`'s predecessor).
  [[nodiscard]] HalfedgeId rotate_ccw(HalfedgeId h) const { return twin(prev(h)); }

  /// Calls `fn(h)` for every outgoing halfedge of `v`, counter-clockwise; for a boundary vertex it starts
  /// after the boundary gap and ends with the outgoing boundary halfedge.
  template <class Fn>
  void for_each_outgoing(VertexId v, Fn&& fn) const {
    const HalfedgeId start = halfedge(v);
    if (!start.valid()) return;
    HalfedgeId h = start;
    do {
      fn(h);
      h = rotate_ccw(h);
    } while (h != start);
  }
  /// Number of edges at `v`.
  [[nodiscard]] int degree(VertexId v) const;

  /// Boundary loops, each as its halfedges in order (next, next, ...).
  [[nodiscard]] std::vector<std::vector<HalfedgeId>> boundary_loops() const;

  /// #F by 3 face list, input order.
  [[nodiscard]] Eigen::MatrixXi faces() const;

  /// Euler characteristic V - E + F, isolated vertices not counted.
  [[nodiscard]] int euler_characteristic() const;

 private:
  std::vector<HalfedgeId> he_next_, he_prev_;
  std::vector<VertexId> he_tail_;
  std::vector<FaceId> he_face_;
  std::vector<HalfedgeId> v_halfedge_;
  std::vector<HalfedgeId> f_halfedge_;
};

}  // namespace liftmap
