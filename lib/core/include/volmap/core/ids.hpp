// volmap/core/ids.hpp — strong typed ids of the tet mesh (VertexId, TetId, HalfFaceId, EdgeId).
// Conventions: an id is a 32-bit index into the mesh's arrays; "none" is kInvalid (0xFFFFFFFF) of
// the right type, never -1 mixed with unsigned. Half-face h = 4t+i is the face of tet t opposite
// its local vertex i, so HalfFaceId::tet() = h>>2 and HalfFaceId::local() = h&3.
// Ids know no mesh: they stay plain values (hashable, comparable, trivially copyable).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

namespace volmap {

inline constexpr std::uint32_t kInvalidIndex = 0xFFFFFFFFu;

// A 32-bit index tagged with the entity it names. Construction from an integer is explicit.
template <class Tag>
class Id {
 public:
  static const Id kInvalid;

  constexpr Id() = default;
  constexpr explicit Id(std::uint32_t index) : index_(index) {}

  constexpr std::uint32_t idx() const { return index_; }
  constexpr bool is_valid() const { return index_ != kInvalidIndex; }

  friend constexpr bool operator==(Id a, Id b) { return a.index_ == b.index_; }
  friend constexpr bool operator!=(Id a, Id b) { return a.index_ != b.index_; }
  friend constexpr bool operator<(Id a, Id b) { return a.index_ < b.index_; }
  friend constexpr bool operator<=(Id a, Id b) { return a.index_ <= b.index_; }
  friend constexpr bool operator>(Id a, Id b) { return a.index_ > b.index_; }
  friend constexpr bool operator>=(Id a, Id b) { return a.index_ >= b.index_; }

 private:
  std::uint32_t index_ = kInvalidIndex;
};

template <class Tag>
constexpr Id<Tag> Id<Tag>::kInvalid{kInvalidIndex};

struct VertexTag {};
struct TetTag {};
struct EdgeTag {};

using VertexId = Id<VertexTag>;
using TetId = Id<TetTag>;
using EdgeId = Id<EdgeTag>;

// Half-face 4t+i: the face of tet t opposite local vertex i.
class HalfFaceId {
 public:
  static const HalfFaceId kInvalid;

  constexpr HalfFaceId() = default;
  constexpr explicit HalfFaceId(std::uint32_t index) : index_(index) {}
  constexpr HalfFaceId(TetId t, int local) : index_(t.idx() * 4u + static_cast<std::uint32_t>(local)) {}

  constexpr std::uint32_t idx() const { return index_; }
  constexpr bool is_valid() const { return index_ != kInvalidIndex; }
  constexpr TetId tet() const { return TetId(index_ >> 2); }
  constexpr int local() const { return static_cast<int>(index_ & 3u); }

  friend constexpr bool operator==(HalfFaceId a, HalfFaceId b) { return a.index_ == b.index_; }
  friend constexpr bool operator!=(HalfFaceId a, HalfFaceId b) { return a.index_ != b.index_; }
  friend constexpr bool operator<(HalfFaceId a, HalfFaceId b) { return a.index_ < b.index_; }
  friend constexpr bool operator<=(HalfFaceId a, HalfFaceId b) { return a.index_ <= b.index_; }
  friend constexpr bool operator>(HalfFaceId a, HalfFaceId b) { return a.index_ > b.index_; }
  friend constexpr bool operator>=(HalfFaceId a, HalfFaceId b) { return a.index_ >= b.index_; }

 private:
  std::uint32_t index_ = kInvalidIndex;
};

inline constexpr HalfFaceId HalfFaceId::kInvalid{kInvalidIndex};

}  // namespace volmap

namespace std {
template <class Tag>
struct hash<volmap::Id<Tag>> {
  std::size_t operator()(volmap::Id<Tag> id) const noexcept { return std::hash<std::uint32_t>()(id.idx()); }
};
template <>
struct hash<volmap::HalfFaceId> {
  std::size_t operator()(volmap::HalfFaceId id) const noexcept { return std::hash<std::uint32_t>()(id.idx()); }
};
}  // namespace std
