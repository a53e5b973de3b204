// volmap/core/properties.hpp — typed per-element property arrays that follow the mesh's edits.
// A VertexProperty<T> / TetProperty<T> is a flat std::vector<T> with one entry per vertex / tet
// SLOT (tombstones included) of one TetMesh. It registers itself with the mesh (RAII): when an edit
// creates a vertex it gets the property's default value; a tet created by splitting or flipping
// copies its parent's value, a tet of a cavity fill the value of the parent the caller named (or the
// default); compact() permutes it with the same old->new map as the mesh.
// Copies have plain value semantics (the copy is registered too and follows later edits on its
// own). Properties hold the mesh's registry, not the mesh: moving the mesh keeps them attached;
// a property outliving its mesh simply stops receiving updates.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace volmap {

enum class ElementKind { Vertex, Tet };

// What the mesh tells each registered property array.
class PropertyArrayBase {
 public:
  virtual ~PropertyArrayBase() = default;
  // Slot `slot` now holds a new element: default value, or a copy of slot `parent` when valid.
  virtual void on_add(std::uint32_t slot, std::uint32_t parent) = 0;
  // Slots slots[k] now hold new elements: each takes the value slot parents[k] held BEFORE this call
  // (default when kInvalidIndex), so a slot may be both a parent and a destination.
  virtual void on_assign(const std::uint32_t* slots, const std::uint32_t* parents, std::size_t n) = 0;
  // compact(): element old -> old_to_new[old] (kInvalidIndex: removed); new size new_size.
  virtual void on_compact(const std::vector<std::uint32_t>& old_to_new, std::size_t new_size) = 0;
};

// The set of properties attached to one mesh (owned by the mesh through a shared_ptr).
class PropertyRegistry {
 public:
  void attach(ElementKind kind, PropertyArrayBase* p) { list(kind).push_back(p); }
  void detach(ElementKind kind, PropertyArrayBase* p) {
    auto& l = list(kind);
    l.erase(std::remove(l.begin(), l.end(), p), l.end());
  }
  void notify_add(ElementKind kind, std::uint32_t slot, std::uint32_t parent) {
    for (PropertyArrayBase* p : list(kind)) p->on_add(slot, parent);
  }
  void notify_assign(ElementKind kind, const std::uint32_t* slots, const std::uint32_t* parents, std::size_t n) {
    for (PropertyArrayBase* p : list(kind)) p->on_assign(slots, parents, n);
  }
  void notify_compact(ElementKind kind, const std::vector<std::uint32_t>& old_to_new, std::size_t new_size) {
    for (PropertyArrayBase* p : list(kind)) p->on_compact(old_to_new, new_size);
  }
  std::size_t size(ElementKind kind) const { return kind == ElementKind::Vertex ? vertex_.size() : tet_.size(); }

 private:
  std::vector<PropertyArrayBase*>& list(ElementKind k) { return k == ElementKind::Vertex ? vertex_ : tet_; }
  std::vector<PropertyArrayBase*> vertex_;
  std::vector<PropertyArrayBase*> tet_;
};

template <class T, ElementKind Kind, class IdT>
class MeshProperty final : public PropertyArrayBase {
 public:
  using value_type = T;
  using reference = typename std::vector<T>::reference;
  using const_reference = typename std::vector<T>::const_reference;

  explicit MeshProperty(const TetMesh& mesh, T default_value = T())
      : registry_(mesh.property_registry_shared()),
        default_(std::move(default_value)),
        data_(Kind == ElementKind::Vertex ? mesh.num_vertex_slots() : mesh.num_tet_slots(), default_) {
    registry_->attach(Kind, this);
  }
  MeshProperty(const MeshProperty& o) : registry_(o.registry_), default_(o.default_), data_(o.data_) {
    registry_->attach(Kind, this);
  }
  MeshProperty& operator=(const MeshProperty& o) {
    if (this == &o) return *this;
    registry_->detach(Kind, this);
    registry_ = o.registry_;
    default_ = o.default_;
    data_ = o.data_;
    registry_->attach(Kind, this);
    return *this;
  }
  ~MeshProperty() override { registry_->detach(Kind, this); }

  reference operator[](IdT id) { return data_[id.idx()]; }
  const_reference operator[](IdT id) const { return data_[id.idx()]; }
  std::size_t size() const { return data_.size(); }
  std::vector<T>& data() { return data_; }
  const std::vector<T>& data() const { return data_; }
  const T& default_value() const { return default_; }
  void fill(const T& v) { std::fill(data_.begin(), data_.end(), v); }

  void on_add(std::uint32_t slot, std::uint32_t parent) override {
    T value = (parent != kInvalidIndex && parent < data_.size()) ? T(data_[parent]) : default_;
    if (slot >= data_.size()) data_.resize(std::size_t(slot) + 1, default_);
    data_[slot] = std::move(value);
  }
  void on_assign(const std::uint32_t* slots, const std::uint32_t* parents, std::size_t n) override {
    std::vector<T> values;
    values.reserve(n);
    for (std::size_t k = 0; k < n; ++k)
      values.push_back((parents[k] != kInvalidIndex && parents[k] < data_.size()) ? T(data_[parents[k]]) : default_);
    for (std::size_t k = 0; k < n; ++k) {
      if (slots[k] >= data_.size()) data_.resize(std::size_t(slots[k]) + 1, default_);
      data_[slots[k]] = std::move(values[k]);
    }
  }
  void on_compact(const std::vector<std::uint32_t>& old_to_new, std::size_t new_size) override {
    std::vector<T> next(new_size, default_);
    const std::size_t n = std::min(old_to_new.size(), data_.size());
    for (std::size_t i = 0; i < n; ++i)
      if (old_to_new[i] != kInvalidIndex) next[old_to_new[i]] = data_[i];
    data_.swap(next);
  }

 private:
  std::shared_ptr<PropertyRegistry> registry_;
  T default_;
  std::vector<T> data_;
};

template <class T>
using VertexProperty = MeshProperty<T, ElementKind::Vertex, VertexId>;
template <class T>
using TetProperty = MeshProperty<T, ElementKind::Tet, TetId>;

// A second coordinate set next to the mesh's own positions (e.g. the target of a map): 3 doubles per
// vertex slot; new vertices get the default (0,0,0) until the caller places them.
using PositionProperty = VertexProperty<std::array<double, 3>>;

}  // namespace volmap
