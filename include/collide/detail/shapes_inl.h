// Inline and template parts of shapes.h.
#pragma once

#include <memory>
#include <type_traits>

namespace collide {

namespace detail {
template <class T> struct IsSharedPtr : std::false_type {};
template <class T> struct IsSharedPtr<std::shared_ptr<T>> : std::true_type {};
}  // namespace detail

template <class F> decltype(auto) Shape::visit(F&& f) const {
  return std::visit(
      [&](const auto& alternative) -> decltype(auto) {
        using T = std::decay_t<decltype(alternative)>;
        if constexpr (detail::IsSharedPtr<T>::value) {
          return f(*alternative);
        } else {
          return f(alternative);
        }
      },
      data_);
}

template <class Visitor>
void TriangleMesh::forEachTriangleOverlapping(const Aabb& box, Visitor&& visit) const {
  // Iterative depth-first walk; the tree is shallow (about log2(triangles / 4) levels).
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = nodes_[stack[--top]];
    if (!node.bounds.overlaps(box)) continue;
    if (node.count > 0) {
      for (std::uint32_t i = 0; i < node.count; ++i) {
        // A leaf's box covers all its triangles; test each one's own box, as shapes.h promises.
        const std::uint32_t index = triangleOrder_[node.firstTriangleOrSecondChild + i];
        const MeshTriangle& t = triangles_[index];
        Aabb triangleBox;
        for (std::uint32_t v : t.v) triangleBox.grow(vertices_[v]);
        if (triangleBox.overlaps(box)) visit(index);
      }
    } else {
      const auto self = static_cast<std::uint32_t>(&node - nodes_.data());
      stack[top++] = node.firstTriangleOrSecondChild;
      stack[top++] = self + 1;
    }
  }
}

inline std::span<const Compound::Child> Compound::children() const { return children_; }

}  // namespace collide
