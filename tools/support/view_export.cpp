// view_export.cpp — packs ViewData into the self-contained volmap-view HTML page.
// Layout of the data blob: arrays one after the other, each starting on a 4-byte boundary,
// little-endian (the only byte order supported); the JSON header names each array's type, byte
// offset and element count (format "volmap-view-1", decoded by viewer/src/data.js).
#include "support/view_export.hpp"

#include <volmap/io/atomic_file.hpp>
#include <volmap/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace volmap {
namespace {

void require(bool ok, const std::string& reason) {
  if (!ok) throw Error(ErrorKind::BadInput, "view data: " + reason);
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '<': out += "\\u003c"; break;  // never "</script" inside the page
      case '>': out += "\\u003e"; break;
      case '&': out += "\\u0026"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

bool little_endian() {
  const std::uint32_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

// Accumulates typed arrays into one blob and their descriptions into the JSON header.
class BlobWriter {
 public:
  void add_f32(const std::string& name, const std::vector<double>& values) {
    std::vector<float> f(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) f[i] = static_cast<float>(values[i]);
    add_raw(name, "f32", f.data(), f.size(), sizeof(float));
  }
  void add_u32(const std::string& name, const std::vector<std::uint32_t>& values) {
    add_raw(name, "u32", values.data(), values.size(), sizeof(std::uint32_t));
  }
  void add_u8(const std::string& name, const std::vector<std::uint8_t>& values) {
    add_raw(name, "u8", values.data(), values.size(), 1);
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  const std::string& descriptions() const { return json_; }

 private:
  void add_raw(const std::string& name, const char* type, const void* data, std::size_t count, std::size_t elem) {
    while (bytes_.size() % 4) bytes_.push_back(0);
    const std::size_t offset = bytes_.size();
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + count * elem);
    if (!json_.empty()) json_ += ",";
    json_ += json_string(name) + ":{\"type\":\"" + type + "\",\"offset\":" + std::to_string(offset) +
             ",\"count\":" + std::to_string(count) + "}";
  }
  std::vector<std::uint8_t> bytes_;
  std::string json_;
};

const char* mode_name(ViewMode mode) {
  switch (mode) {
    case ViewMode::Mesh: return "mesh";
    case ViewMode::VolumeMap: return "volume-map";
    case ViewMode::BoundaryMap: return "boundary-map";
  }
  return "mesh";
}

}  // namespace

void validate_view_data(const ViewData& d) {
  require(d.source_xyz.size() % 3 == 0, "source coordinates are not 3 per vertex");
  require(d.tets.size() % 4 == 0, "tets are not 4 ids each");
  const std::size_t nv = d.num_vertices(), nt = d.num_tets();
  require(nt > 0, "no tets");
  for (std::uint32_t id : d.tets) require(id < nv, "a tet references vertex " + std::to_string(id) + " >= " + std::to_string(nv));
  require(d.flags.size() == nt, "flags are not one per tet");
  require(d.volume_in.empty() || d.volume_in.size() == nt, "source volumes are not one per tet");
  require(d.volume_out.empty() || d.volume_out.size() == nt, "target volumes are not one per tet");
  require(d.sigma.empty() || d.sigma.size() == 3 * nt, "singular values are not 3 per tet");
  if (d.mode == ViewMode::Mesh) {
    require(d.target_xyz.empty(), "a single mesh has no target positions");
  } else {
    require(d.target_xyz.size() == 3 * nv, "target positions are not 3 per vertex");
  }
  for (const auto& f : d.fields) {
    require(!f.key.empty(), "a field has no key");
    require(f.values.size() == nt, "field " + f.key + " is not one value per tet");
    require(f.lower < f.upper, "field " + f.key + " has an empty clamp range");
  }
}

ViewSummary summarize_view(const ViewData& d) {
  ViewSummary s;
  s.num_tets = d.num_tets();
  s.num_vertices = d.num_vertices();
  for (std::uint8_t f : d.flags) {
    s.num_inverted += (f & kViewInverted) ? 1 : 0;
    s.num_degenerate += (f & kViewDegenerate) ? 1 : 0;
    s.num_source_nonpositive += (f & kViewSourceNonPositive) ? 1 : 0;
  }
  const std::vector<double>& weights = d.mode == ViewMode::VolumeMap && !d.volume_out.empty() ? d.volume_out : d.volume_in;
  for (const auto& f : d.fields) {
    ViewFieldSummary fs;
    fs.key = f.key;
    // VOLMAP metrics rules (volmap-reference.md §7): valid tets only, non-finite -> upper, clamp,
    // min starts at upper and max at lower, E = sum(d |V|) / sum(|V|).
    double mn = f.upper, mx = f.lower, num = 0, den = 0;
    for (std::size_t t = 0; t < f.values.size(); ++t) {
      if (f.valid_only && (d.flags[t] & (kViewInverted | kViewDegenerate))) continue;
      double v = f.values[t];
      if (!std::isfinite(v)) v = f.upper;
      v = std::min(f.upper, std::max(f.lower, v));
      mn = std::min(mn, v);
      mx = std::max(mx, v);
      const double w = f.volume_weighted && !weights.empty() ? std::fabs(weights[t]) : 1.0;
      num += v * w;
      den += w;
      ++fs.count;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    fs.min = fs.count ? mn : nan;
    fs.max = fs.count ? mx : nan;
    fs.weighted_mean = fs.count && den > 0 ? num / den : nan;
    s.fields.push_back(fs);
  }
  return s;
}

std::string base64_encode(const std::uint8_t* bytes, std::size_t size) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += alphabet[v & 63];
  }
  if (i + 1 == size) {
    const std::uint32_t v = std::uint32_t(bytes[i]) << 16;
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == size) {
    const std::uint32_t v = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string build_view_html(const ViewData& d, const std::string& viewer_bundle) {
  validate_view_data(d);
  if (!little_endian()) throw Error(ErrorKind::Unsupported, "view export: big-endian hosts are not supported");
  require(!viewer_bundle.empty(), "the viewer bundle is empty (build viewer/: npm ci && npm run build)");
  std::string lower_bundle(viewer_bundle.size(), ' ');
  std::transform(viewer_bundle.begin(), viewer_bundle.end(), lower_bundle.begin(),
                 [](char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  require(lower_bundle.find("</script") == std::string::npos, "the viewer bundle contains \"</script\" and cannot be inlined");

  BlobWriter blob;
  blob.add_f32("source_xyz", d.source_xyz);
  blob.add_u32("tets", d.tets);
  blob.add_u8("flags", d.flags);
  if (!d.target_xyz.empty()) blob.add_f32("target_xyz", d.target_xyz);
  if (!d.volume_in.empty()) blob.add_f32("volume_in", d.volume_in);
  if (!d.volume_out.empty()) blob.add_f32("volume_out", d.volume_out);
  if (!d.sigma.empty()) blob.add_f32("sigma", d.sigma);
  for (const auto& f : d.fields) blob.add_f32("field_" + f.key, f.values);

  const ViewSummary summary = summarize_view(d);
  std::string meta = "{\"format\":\"volmap-view-1\"";
  meta += ",\"mode\":" + json_string(mode_name(d.mode));
  meta += ",\"title\":" + json_string(d.title);
  meta += ",\"source_name\":" + json_string(d.source_name);
  meta += ",\"target_name\":" + json_string(d.target_name);
  meta += ",\"num_vertices\":" + std::to_string(d.num_vertices());
  meta += ",\"num_tets\":" + std::to_string(d.num_tets());
  meta += ",\"num_boundary_faces\":" + std::to_string(d.num_boundary_faces);
  meta += ",\"initial_field\":" + json_string(d.initial_field);
  meta += ",\"fields\":[";
  for (std::size_t i = 0; i < d.fields.size(); ++i) {
    const auto& f = d.fields[i];
    if (i) meta += ",";
    meta += "{\"key\":" + json_string(f.key) + ",\"label\":" + json_string(f.label) +
            ",\"lower\":" + json_number(f.lower) + ",\"upper\":" + json_number(f.upper) +
            ",\"worse\":\"" + (f.worse_high ? "high" : "low") + "\"" +
            ",\"valid_only\":" + (f.valid_only ? "true" : "false") + "}";
  }
  meta += "],\"summary\":{\"num_inverted\":" + std::to_string(summary.num_inverted) +
          ",\"num_degenerate\":" + std::to_string(summary.num_degenerate) +
          ",\"num_source_nonpositive\":" + std::to_string(summary.num_source_nonpositive) + ",\"fields\":{";
  for (std::size_t i = 0; i < summary.fields.size(); ++i) {
    const auto& fs = summary.fields[i];
    const auto& f = d.fields[i];
    if (i) meta += ",";
    const std::string weighting = !f.volume_weighted ? "unweighted"
                                  : d.mode == ViewMode::VolumeMap && !d.volume_out.empty() ? "|target volume|"
                                                                                          : "|source volume|";
    meta += json_string(fs.key) + ":{\"count\":" + std::to_string(fs.count) + ",\"min\":" + json_number(fs.min) +
            ",\"max\":" + json_number(fs.max) + ",\"weighted_mean\":" + json_number(fs.weighted_mean) +
            ",\"weighting\":" + json_string(weighting + (f.valid_only ? ", valid tets" : "")) + "}";
  }
  meta += "}},\"byte_length\":" + std::to_string(blob.bytes().size());
  meta += ",\"arrays\":{" + blob.descriptions() + "}}";

  std::string html;
  const std::string data64 = base64_encode(blob.bytes().data(), blob.bytes().size());
  html.reserve(data64.size() + viewer_bundle.size() + meta.size() + 1024);
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<meta name=\"generator\" content=\"volmap-view\">\n";
  html += "<title>volmap-view: " + html_escape(d.title) + "</title>\n</head>\n<body>\n";
  html += "<script type=\"application/json\" id=\"volmap-meta\">" + meta + "</script>\n";
  html += "<script type=\"application/octet-stream\" id=\"volmap-data\">" + data64 + "</script>\n";
  html += "<script>\n" + viewer_bundle + "\n</script>\n</body>\n</html>\n";
  return html;
}

void write_view_html(const std::string& path, const ViewData& data, const std::string& viewer_bundle) {
  write_text_atomically(path, build_view_html(data, viewer_bundle));
}

}  // namespace volmap
