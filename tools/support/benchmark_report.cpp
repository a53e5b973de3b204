// HTML + SVG benchmark report. Plots are drawn here as plain SVG (no scripts, no external assets):
// success rate per group and domain, per-case distributions of MIPS3D and conformal distortion
// sorted by value (the style of Fig. 7 of the VOLMAP paper), inverted tets, time and growth.
// The Markdown mapping table is the per-domain table (certified at fixed connectivity / with
// refinement, growth, time, distortion means), meant to be pasted in notes as it is.
#include "support/benchmark_report.hpp"
#include "support/dataset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace volmap {
namespace {

const char* kColors[] = {"#7b3fa0", "#2e9d5b", "#d9822b", "#2b6cd9", "#c0392b", "#555555"};

std::string fmt(double v, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}
std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}
double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A scatter/line plot of sorted per-case values, one series per method; optional log y axis.
struct Series {
  std::string label;
  std::vector<double> values;  // plotted against their rank 1..n after sorting
};
std::string sorted_values_plot(const std::string& title, const std::string& y_label, std::vector<Series> series,
                               bool log_y) {
  const double W = 560, H = 300, L = 64, R = 16, T = 30, B = 44;
  double lo = INFINITY, hi = -INFINITY;
  std::size_t n_max = 1;
  for (auto& s : series) {
    std::sort(s.values.begin(), s.values.end());
    n_max = std::max(n_max, s.values.size());
    for (double v : s.values) {
      if (!std::isfinite(v) || (log_y && v <= 0)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' class='plot'>"
      << "<text x='" << W / 2 << "' y='18' text-anchor='middle' class='title'>" << escape(title) << "</text>";
  if (!(lo <= hi)) {
    svg << "<text x='" << W / 2 << "' y='" << H / 2 << "' text-anchor='middle'>no data</text></svg>";
    return svg.str();
  }
  if (log_y) {
    lo = std::pow(10.0, std::floor(std::log10(lo)));
    hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (hi <= lo) hi = lo * 10;
  } else {
    if (hi == lo) hi = lo + 1;
    const double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
  }
  auto ty = [&](double v) {
    const double f = log_y ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return T + (1 - f) * (H - T - B);
  };
  auto tx = [&](double rank) { return L + (n_max > 1 ? rank / double(n_max - 1) : 0.5) * (W - L - R); };
  svg << "<rect x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B
      << "' fill='none' stroke='#999'/>";
  // y ticks
  std::vector<double> ticks;
  if (log_y)
    for (double v = lo; v <= hi * 1.0001; v *= 10) ticks.push_back(v);
  else
    for (int i = 0; i <= 4; ++i) ticks.push_back(lo + (hi - lo) * i / 4);
  for (double v : ticks) {
    svg << "<line x1='" << L - 4 << "' x2='" << W - R << "' y1='" << ty(v) << "' y2='" << ty(v)
        << "' stroke='#eee'/><text x='" << L - 6 << "' y='" << ty(v) + 4 << "' text-anchor='end' class='tick'>"
        << fmt(v) << "</text>";
  }
  svg << "<text x='" << W / 2 << "' y='" << H - 8 << "' text-anchor='middle' class='axis'>cases, sorted by value</text>"
      << "<text transform='translate(14," << (T + H - B) / 2 << ") rotate(-90)' text-anchor='middle' class='axis'>"
      << escape(y_label) << "</text>";
  for (std::size_t k = 0; k < series.size(); ++k) {
    const char* color = kColors[k % 6];
    svg << "<polyline fill='none' stroke='" << color << "' stroke-width='1.5' points='";
    std::size_t rank = 0;
    for (double v : series[k].values) {
      if (std::isfinite(v) && !(log_y && v <= 0)) svg << tx(double(rank)) << "," << ty(v) << " ";
      ++rank;
    }
    svg << "'/>";
    svg << "<rect x='" << L + 10 << "' y='" << T + 8 + 16 * k << "' width='10' height='10' fill='" << color
        << "'/><text x='" << L + 26 << "' y='" << T + 17 + 16 * k << "' class='tick'>" << escape(series[k].label)
        << " (" << series[k].values.size() << ")</text>";
  }
  svg << "</svg>";
  return svg.str();
}

// Grouped bars: success rate per (group, domain), one bar per method.
std::string success_bars(const std::vector<MethodRun>& runs) {
  std::vector<std::string> keys;
  std::vector<std::map<std::string, double>> rates(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k)
    for (const auto& row : summarize(runs[k])) {
      const std::string key = row.group + " " + row.domain;
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
      rates[k][key] = row.success_rate;
    }
  const double L = 48, T = 30, B = 60, H = 300, group_w = std::max(40.0, 14.0 * runs.size() + 16);
  const double W = std::max(520.0, L + 170 + group_w * std::max<std::size_t>(keys.size(), 1));
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' class='plot'>"
      << "<text x='" << W / 2 << "' y='18' text-anchor='middle' class='title'>certified maps per group and domain (%)</text>";
  auto ty = [&](double f) { return T + (1 - f) * (H - T - B); };
  for (int i = 0; i <= 4; ++i) {
    const double f = i / 4.0;
    svg << "<line x1='" << L << "' x2='" << W - 16 << "' y1='" << ty(f) << "' y2='" << ty(f) << "' stroke='#eee'/>"
        << "<text x='" << L - 6 << "' y='" << ty(f) + 4 << "' text-anchor='end' class='tick'>" << int(f * 100) << "</text>";
  }
  for (std::size_t g = 0; g < keys.size(); ++g) {
    const double x0 = L + 8 + g * group_w;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      auto it = rates[k].find(keys[g]);
      if (it == rates[k].end()) continue;
      const double x = x0 + 14.0 * k;
      svg << "<rect x='" << x << "' y='" << ty(it->second) << "' width='12' height='" << ty(0) - ty(it->second)
          << "' fill='" << kColors[k % 6] << "'><title>" << escape(runs[k].label + " " + keys[g]) << ": "
          << fmt(100 * it->second, 4) << "%</title></rect>";
    }
    svg << "<text transform='translate(" << x0 + 6 << "," << H - B + 12 << ") rotate(45)' class='tick'>"
        << escape(keys[g]) << "</text>";
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    svg << "<rect x='" << W - 150 << "' y='" << T + 16 * k << "' width='10' height='10' fill='" << kColors[k % 6]
        << "'/><text x='" << W - 134 << "' y='" << T + 9 + 16 * k << "' class='tick'>" << escape(runs[k].label) << "</text>";
  svg << "</svg>";
  return svg.str();
}

}  // namespace

std::vector<SummaryRow> summarize(const MethodRun& run) {
  std::map<std::pair<std::string, std::string>, std::vector<const CaseRecord*>> by_key;
  for (const auto& r : run.records) by_key[{r.group, r.domain}].push_back(&r);
  std::vector<SummaryRow> rows;
  for (const auto& [key, recs] : by_key) {
    SummaryRow row;
    row.method = run.label;
    row.group = key.first;
    row.domain = key.second;
    std::vector<double> times, growths, mips, conf, mips_all, conf_all;
    for (const auto* r : recs) {
      ++row.cases;
      if (r->certified) ++row.certified;
      if (r->timed_out) ++row.timed_out;
      if (r->term_signal != 0) ++row.crashed;
      times.push_back(r->time_s);
      growths.push_back(r->growth);
      if (r->mips3d) mips_all.push_back(*r->mips3d);
      if (r->conformal) conf_all.push_back(*r->conformal);
      if (r->certified && r->mips3d) mips.push_back(*r->mips3d);
      if (r->certified && r->conformal) conf.push_back(*r->conformal);
    }
    row.success_rate = row.cases ? double(row.certified) / double(row.cases) : 0;
    row.median_time_s = median(times);
    row.max_time_s = times.empty() ? 0 : *std::max_element(times.begin(), times.end());
    row.median_growth = median(growths);
    row.max_growth = growths.empty() ? 1 : *std::max_element(growths.begin(), growths.end());
    auto mean = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += x;
      return v.empty() ? 0.0 : sum / double(v.size());
    };
    row.mean_mips3d = mean(mips);
    row.mean_conformal = mean(conf);
    row.mean_mips3d_all = mean(mips_all);
    row.mean_conformal_all = mean(conf_all);
    rows.push_back(row);
  }
  return rows;
}

bool within_growth_budget(const CaseRecord& r) {
  // Integer test: a float ratio 105/100 - 1 is 0.05000000000000004, just over the budget.
  if (r.tets_in > 0 && r.tets_out > 0) return 100 * (r.tets_out - r.tets_in) <= 5 * r.tets_in;
  return r.growth - 1.0 <= 0.05 + 1e-12;
}

namespace {

// Added tets as a fraction of the input's, (out - in) / in.
double added_fraction(const CaseRecord& r) {
  if (r.tets_in > 0 && r.tets_out > 0) return double(r.tets_out - r.tets_in) / double(r.tets_in);
  return r.growth - 1.0;
}

// VOLMAP domains first in their canonical order, then any other name alphabetically.
bool domain_before(const std::string& a, const std::string& b) {
  const auto& order = volmap_domain_suffixes();
  const auto ra = std::find(order.begin(), order.end(), a) - order.begin();
  const auto rb = std::find(order.begin(), order.end(), b) - order.begin();
  return ra != rb ? ra < rb : a < b;
}
// "G2" before "G10".
bool group_before(const std::string& a, const std::string& b) {
  return a.size() != b.size() ? a.size() < b.size() : a < b;
}

std::optional<double> mean_of(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  double sum = 0;
  for (double x : v) sum += x;
  return sum / double(v.size());
}

MappingTableRow table_row(const std::string& label, const std::string& group, const std::string& domain,
                          const std::vector<const CaseRecord*>& records) {
  MappingTableRow row;
  row.label = label;
  row.group = group;
  row.domain = domain;
  std::vector<double> growths, times, mips, conformal;
  for (const auto* r : records) {
    ++row.pairs;
    times.push_back(r->time_s);
    if (!r->certified) continue;
    ++row.certified;
    if (!r->refined) ++row.certified_fixed;
    if (within_growth_budget(*r)) ++row.certified_small_growth;
    growths.push_back(added_fraction(*r));
    if (r->mips3d) mips.push_back(*r->mips3d);
    if (r->conformal) conformal.push_back(*r->conformal);
  }
  row.growth_median = median(growths);
  row.growth_max = growths.empty() ? 0 : *std::max_element(growths.begin(), growths.end());
  row.time_median_s = median(times);
  row.time_max_s = times.empty() ? 0 : *std::max_element(times.begin(), times.end());
  row.mean_mips3d = mean_of(mips);
  row.mean_conformal = mean_of(conformal);
  return row;
}

std::vector<std::string> sorted_groups(const std::vector<const MethodRun*>& runs) {
  std::set<std::string> set;
  for (const auto* run : runs)
    for (const auto& r : run->records) set.insert(r.group);
  std::vector<std::string> groups(set.begin(), set.end());
  std::sort(groups.begin(), groups.end(), group_before);
  return groups;
}

std::string markdown_cell(std::string text) {
  std::replace(text.begin(), text.end(), '|', '/');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f %%", 100 * fraction);
  return buf;
}
std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

std::vector<MappingTableRow> mapping_table(const MethodRun& run) {
  std::vector<MappingTableRow> rows;
  for (const auto& group : sorted_groups({&run})) {
    std::map<std::string, std::vector<const CaseRecord*>> by_domain;
    std::vector<const CaseRecord*> all;
    for (const auto& r : run.records)
      if (r.group == group) {
        by_domain[r.domain].push_back(&r);
        all.push_back(&r);
      }
    std::vector<std::string> domains;
    for (const auto& entry : by_domain) domains.push_back(entry.first);
    std::sort(domains.begin(), domains.end(), domain_before);
    for (const auto& d : domains) rows.push_back(table_row(run.label, group, d, by_domain[d]));
    rows.push_back(table_row(run.label, group, "all", all));
  }
  return rows;
}

std::string mapping_table_markdown(const std::vector<MethodRun>& runs) {
  std::ostringstream md;
  md << "Certified = the exact check of volmap-map-check passed on the files the method wrote. "
        "Growth = (output tets - input tets) / input tets, over certified pairs; fixed connectivity = "
        "certified without refinement; growth <= 5 % counts those too. Time = the method's wall-clock "
        "seconds per pair, over all pairs. MIPS3D and conformal = VOLMAP's volume-weighted means, "
        "averaged over certified pairs.\n";
  for (const auto& run : runs) {
    std::set<std::string> methods, arguments;
    for (const auto& r : run.records) {
      methods.insert(r.method);
      arguments.insert(r.method_args);
    }
    std::string method_list, argument_list;
    for (const auto& m : methods) method_list += (method_list.empty() ? "`" : ", `") + m + "`";
    for (const auto& a : arguments) argument_list += (argument_list.empty() ? "`" : ", `") + (a.empty() ? "(none)" : a) + "`";
    const auto rows = mapping_table(run);
    for (const auto& group : sorted_groups({&run})) {
      md << "\n### " << markdown_cell(run.label) << " - " << group << "\n\nmethod " << method_list << ", arguments "
         << argument_list << "\n\n"
         << "| domain | pairs | certified | fixed connectivity | growth <= 5 % | growth median / max | "
            "time median / max (s) | MIPS3D | conformal |\n"
         << "|:--|--:|--:|--:|--:|--:|--:|--:|--:|\n";
      for (const auto& row : rows) {
        if (row.group != group) continue;
        const bool total = row.domain == "all";
        const auto b = [&](const std::string& text) { return total ? "**" + text + "**" : text; };
        md << "| " << b(row.domain) << " | " << row.pairs << " | " << b(std::to_string(row.certified)) << " | "
           << row.certified_fixed << " | " << row.certified_small_growth << " | "
           << (row.certified ? percent(row.growth_median) + " / " + percent(row.growth_max) : "-") << " | "
           << fixed(row.time_median_s, 2) << " / " << fixed(row.time_max_s, 2) << " | "
           << (row.mean_mips3d ? fixed(*row.mean_mips3d, 3) : "-") << " | "
           << (row.mean_conformal ? fixed(*row.mean_conformal, 3) : "-") << " |\n";
      }
      std::vector<const CaseRecord*> failed;
      for (const auto& r : run.records)
        if (r.group == group && !r.certified) failed.push_back(&r);
      md << "\nNot certified (" << failed.size() << ")" << (failed.empty() ? "." : ":") << "\n";
      for (const auto* r : failed) {
        md << "- " << r->case_id << " (" << (r->timed_out ? std::string("timed out") : "exit " + std::to_string(r->exit_code));
        if (r->negative >= 0 && r->zero >= 0) md << ", " << r->negative + r->zero << " non-positive tets";
        if (!r->failure.empty()) md << ", " << markdown_cell(r->failure.substr(0, 120));
        md << ")\n";
      }
    }
  }
  // Every run's certified count side by side, per group and domain.
  if (runs.size() > 1) {
    md << "\n### certified pairs side by side\n\n| group | domain |";
    for (const auto& run : runs) md << " " << markdown_cell(run.label) << " |";
    md << "\n|:--|:--|";
    for (std::size_t k = 0; k < runs.size(); ++k) md << "--:|";
    md << "\n";
    std::vector<std::vector<MappingTableRow>> tables;
    for (const auto& run : runs) tables.push_back(mapping_table(run));
    std::vector<const MethodRun*> all_runs;
    for (const auto& run : runs) all_runs.push_back(&run);
    for (const auto& group : sorted_groups(all_runs)) {
      std::set<std::string> seen;
      std::vector<std::string> domains;
      for (const auto& t : tables)
        for (const auto& row : t)
          if (row.group == group && row.domain != "all" && seen.insert(row.domain).second) domains.push_back(row.domain);
      std::sort(domains.begin(), domains.end(), domain_before);
      domains.push_back("all");
      for (const auto& d : domains) {
        md << "| " << group << " | " << d << " |";
        for (const auto& t : tables) {
          const auto it = std::find_if(t.begin(), t.end(), [&](const auto& row) { return row.group == group && row.domain == d; });
          if (it == t.end()) md << " - |";
          else md << " " << it->certified << "/" << it->pairs << " |";
        }
        md << "\n";
      }
    }
  }
  return md.str();
}

std::string summary_csv(const std::vector<MethodRun>& runs) {
  std::ostringstream csv;
  csv << "method,group,domain,cases,certified,success_rate,timed_out,crashed,median_time_s,max_time_s,"
         "median_growth,max_growth,mean_mips3d_certified,mean_conformal_certified,mean_mips3d_all,mean_conformal_all\n";
  for (const auto& run : runs)
    for (const auto& r : summarize(run))
      csv << r.method << ',' << r.group << ',' << r.domain << ',' << r.cases << ',' << r.certified << ','
          << fmt(r.success_rate, 6) << ',' << r.timed_out << ',' << r.crashed << ',' << fmt(r.median_time_s, 6) << ','
          << fmt(r.max_time_s, 6) << ',' << fmt(r.median_growth, 6) << ',' << fmt(r.max_growth, 6) << ','
          << fmt(r.mean_mips3d, 6) << ',' << fmt(r.mean_conformal, 6) << ',' << fmt(r.mean_mips3d_all, 6) << ','
          << fmt(r.mean_conformal_all, 6) << '\n';
  return csv.str();
}

std::string render_report_html(const std::vector<MethodRun>& runs, const std::string& title) {
  std::ostringstream html;
  html << "<!DOCTYPE html><html><head><meta charset='utf-8'><title>" << escape(title) << "</title><style>"
       << "body{font-family:sans-serif;margin:24px;color:#222}table{border-collapse:collapse;margin:12px 0}"
       << "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f3f3f3}"
       << ".plot{margin:8px;border:1px solid #ddd;background:#fff}.title{font-size:14px;font-weight:bold}"
       << ".tick{font-size:10px}.axis{font-size:12px}.plots{display:flex;flex-wrap:wrap}"
       << "</style></head><body><h1>" << escape(title) << "</h1>";
  html << "<p>Certified = the exact check (volmap-map-check, exact orient3d on the written numbers, boundary"
          " bit-exact) passed on what the method wrote. Energies are VOLMAP's output-volume-weighted means.</p>";
  html << "<table><tr><th>method</th><th>group</th><th>domain</th><th>cases</th><th>certified</th><th>%</th>"
          "<th>timeouts</th><th>crashes</th><th>median s</th><th>max s</th><th>median growth</th><th>max growth</th>"
          "<th>mean MIPS3D<br>certified</th><th>mean conformal<br>certified</th><th>mean MIPS3D<br>all maps</th>"
          "<th>mean conformal<br>all maps</th></tr>";
  for (const auto& run : runs)
    for (const auto& r : summarize(run))
      html << "<tr><td>" << escape(r.method) << "</td><td>" << escape(r.group) << "</td><td>" << escape(r.domain)
           << "</td><td>" << r.cases << "</td><td>" << r.certified << "</td><td>" << fmt(100 * r.success_rate, 4)
           << "</td><td>" << r.timed_out << "</td><td>" << r.crashed << "</td><td>" << fmt(r.median_time_s)
           << "</td><td>" << fmt(r.max_time_s) << "</td><td>" << fmt(r.median_growth, 4) << "</td><td>"
           << fmt(r.max_growth, 4) << "</td><td>" << (r.certified ? fmt(r.mean_mips3d, 4) : "–") << "</td><td>"
           << (r.certified ? fmt(r.mean_conformal, 4) : "–") << "</td><td>" << fmt(r.mean_mips3d_all, 4) << "</td><td>"
           << fmt(r.mean_conformal_all, 4) << "</td></tr>";
  html << "</table><div class='plots'>" << success_bars(runs);

  auto collect = [&](auto getter) {
    std::vector<Series> series;
    for (const auto& run : runs) {
      Series s{run.label, {}};
      for (const auto& r : run.records)
        if (auto v = getter(r)) s.values.push_back(*v);
      series.push_back(std::move(s));
    }
    return series;
  };
  html << sorted_values_plot("MIPS3D per map (weighted mean)", "MIPS3D",
                             collect([](const CaseRecord& r) { return r.mips3d; }), true);
  html << sorted_values_plot("conformal distortion per map", "conformal",
                             collect([](const CaseRecord& r) { return r.conformal; }), true);
  html << sorted_values_plot("non-positive tets per map (+1, log)", "inverted + degenerate + 1",
                             collect([](const CaseRecord& r) -> std::optional<double> {
                               if (r.negative < 0 || r.zero < 0) return std::nullopt;
                               return double(r.negative + r.zero + 1);
                             }),
                             true);
  html << sorted_values_plot("time per case (s)", "seconds",
                             collect([](const CaseRecord& r) -> std::optional<double> { return std::max(r.time_s, 1e-3); }),
                             true);
  html << sorted_values_plot("growth (output tets / input tets)", "growth",
                             collect([](const CaseRecord& r) -> std::optional<double> {
                               if (r.tets_out < 0) return std::nullopt;
                               return r.growth;
                             }),
                             false);
  html << "</div>";
  // Failures list (first 200 per method) so a reader sees why cases failed.
  for (const auto& run : runs) {
    std::size_t shown = 0;
    html << "<h2>" << escape(run.label) << ": cases not certified</h2><table><tr><th>case</th><th>exit</th>"
            "<th>inverted</th><th>zero</th><th>reason</th></tr>";
    for (const auto& r : run.records) {
      if (r.certified || shown++ >= 200) continue;
      html << "<tr><td>" << escape(r.case_id) << "</td><td>" << r.exit_code << "</td><td>" << r.negative << "</td><td>"
           << r.zero << "</td><td style='text-align:left'>" << escape(r.failure) << "</td></tr>";
    }
    html << "</table>";
  }
  html << "</body></html>\n";
  return html.str();
}

}  // namespace volmap
