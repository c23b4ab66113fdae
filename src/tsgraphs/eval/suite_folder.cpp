#include "tsgraphs/eval/suite_folder.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/text_file.hpp"

namespace tsgraphs::eval {
namespace {

using ordered_json = nlohmann::ordered_json;

nlohmann::json value(const Figure& f) {
  return f && std::isfinite(*f) ? nlohmann::json(*f) : nlohmann::json(nullptr);
}

ordered_json parse_json(const std::string& text, const std::string& file) {
  try {
    return ordered_json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw input_error(file, 0, std::string("not valid JSON: ") + e.what());
  }
}

/// The string at `key` of `j`; an InputError naming the key when absent or not a string.
std::string string_at(const ordered_json& j, const char* key, const std::string& file,
                      const std::string& where = "") {
  const std::string path = where.empty() ? key : where + "." + key;
  if (!j.is_object() || !j.contains(key) || !j[key].is_string())
    throw input_error(file, 0, path + ": expected a string");
  return j[key].get<std::string>();
}

Figure figure_at(const ordered_json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return std::nullopt;
  const double v = j[key].get<double>();
  return std::isfinite(v) ? Figure(v) : std::nullopt;
}

std::vector<std::string> flatten_keys(const std::string& metrics_text) {
  std::vector<std::string> keys;
  const ordered_json j = ordered_json::parse(metrics_text);
  for (const auto& [group, figures] : j.items())
    for (const auto& [key, v] : figures.items()) keys.push_back(group + "." + key);
  return keys;
}

}  // namespace

Figure CaseMethod::figure(const std::string& key) const {
  const auto it = figures.find(key);
  return it == figures.end() ? std::nullopt : it->second;
}

const CaseMethod* CaseRecord::method(const std::string& slug) const {
  for (const CaseMethod& m : methods)
    if (m.method.slug == slug) return &m;
  return nullptr;
}

std::string CaseRecord::info_value(const std::string& key) const {
  for (const auto& [k, v] : info)
    if (k == key) return v;
  return "";
}

const std::vector<std::string>& case_info_keys() {
  // source: the scene file, built-in scene or sequence folder; platform: the suite's platform
  // name ("default": the generator's own draw); carrier: wheeled, handheld or legged (the
  // scene's platform type); levels and rooms: of the ground truth.
  static const std::vector<std::string> keys = {"source",   "style",  "seed",         "size",
                                                "platform", "preset", "mount_height", "carrier",
                                                "rate_hz",  "laps",   "levels",       "rooms"};
  return keys;
}

std::string case_record_json(const CaseRecord& r) {
  ordered_json j;
  j["id"] = r.id;
  j["kind"] = r.kind;
  j["spec"] = r.spec;
  j["status"] = r.status;
  j["message"] = r.message;
  j["wall_s"] = r.wall_s;
  j["info"] = ordered_json::object();
  for (const auto& [k, v] : r.info) j["info"][k] = v;
  j["methods"] = ordered_json::array();
  for (const CaseMethod& m : r.methods) {
    ordered_json jm;
    jm["slug"] = m.method.slug;
    jm["name"] = m.method.name;
    jm["wall_s"] = value(m.wall_s);
    jm["figures"] = ordered_json::object();
    // metrics.json's order first, then any key it does not know (a newer eval's).
    for (const std::string& key : metrics_keys()) jm["figures"][key] = value(m.figure(key));
    for (const auto& [key, f] : m.figures)
      if (!jm["figures"].contains(key)) jm["figures"][key] = value(f);
    j["methods"].push_back(std::move(jm));
  }
  return j.dump(1) + "\n";
}

CaseRecord parse_case_record(const std::string& text, const std::string& file) {
  const ordered_json j = parse_json(text, file);
  if (!j.is_object()) throw input_error(file, 0, "expected a JSON object");
  CaseRecord r;
  r.id = string_at(j, "id", file);
  r.kind = string_at(j, "kind", file);
  if (j.contains("spec") && j["spec"].is_string()) r.spec = j["spec"].get<std::string>();
  r.status = string_at(j, "status", file);
  if (r.status != kCaseDone && r.status != kCaseFailed)
    throw input_error(file, 0, "status: '" + r.status + "': expected done or failed");
  if (j.contains("message") && j["message"].is_string()) r.message = j["message"].get<std::string>();
  r.wall_s = figure_at(j, "wall_s").value_or(0.0);
  if (j.contains("info") && j["info"].is_object()) {
    for (const auto& [k, v] : j["info"].items())
      if (v.is_string()) r.info.emplace_back(k, v.get<std::string>());
  }
  if (j.contains("methods")) {
    if (!j["methods"].is_array()) throw input_error(file, 0, "methods: expected a list");
    for (std::size_t i = 0; i < j["methods"].size(); ++i) {
      const ordered_json& jm = j["methods"][i];
      const std::string where = "methods[" + std::to_string(i) + "]";
      CaseMethod m;
      m.method.slug = string_at(jm, "slug", file, where);
      m.method.name = string_at(jm, "name", file, where);
      m.wall_s = figure_at(jm, "wall_s");
      if (jm.contains("figures") && jm["figures"].is_object())
        for (const auto& [key, v] : jm["figures"].items())
          m.figures[key] = figure_at(jm["figures"], key.c_str());
      r.methods.push_back(std::move(m));
    }
  }
  return r;
}

CaseRecord read_case_record(const std::string& file) { return parse_case_record(read_text_file(file), file); }

std::string suite_index_json(const SuiteIndex& index) {
  ordered_json j;
  j["name"] = index.name;
  j["suite_file"] = index.suite_file;
  j["methods"] = ordered_json::array();
  for (const SuiteMethod& m : index.methods) j["methods"].push_back({{"slug", m.slug}, {"name", m.name}});
  j["cases"] = index.case_ids;
  j["groups"] = ordered_json::array();
  for (const CaseGroup& g : index.groups) j["groups"].push_back({{"name", g.name}, {"cases", g.case_ids}});
  return j.dump(1) + "\n";
}

SuiteIndex read_suite_index(const std::string& file) {
  const ordered_json j = parse_json(read_text_file(file), file);
  SuiteIndex index;
  index.name = string_at(j, "name", file);
  if (j.contains("suite_file") && j["suite_file"].is_string())
    index.suite_file = j["suite_file"].get<std::string>();
  if (!j.contains("methods") || !j["methods"].is_array())
    throw input_error(file, 0, "methods: expected a list");
  for (std::size_t i = 0; i < j["methods"].size(); ++i) {
    const std::string where = "methods[" + std::to_string(i) + "]";
    index.methods.push_back(
        {string_at(j["methods"][i], "slug", file, where), string_at(j["methods"][i], "name", file, where)});
  }
  if (!j.contains("cases") || !j["cases"].is_array()) throw input_error(file, 0, "cases: expected a list");
  for (const auto& id : j["cases"]) {
    if (!id.is_string()) throw input_error(file, 0, "cases: expected a list of case ids");
    index.case_ids.push_back(id.get<std::string>());
  }
  if (j.contains("groups")) {  // absent in folders written before groups existed
    if (!j["groups"].is_array()) throw input_error(file, 0, "groups: expected a list");
    for (std::size_t i = 0; i < j["groups"].size(); ++i) {
      const ordered_json& g = j["groups"][i];
      const std::string where = "groups[" + std::to_string(i) + "]";
      CaseGroup group{string_at(g, "name", file, where), {}};
      if (!g.contains("cases") || !g["cases"].is_array())
        throw input_error(file, 0, where + ".cases: expected a list");
      for (const auto& id : g["cases"]) {
        if (!id.is_string()) throw input_error(file, 0, where + ".cases: expected a list of case ids");
        group.case_ids.push_back(id.get<std::string>());
      }
      index.groups.push_back(std::move(group));
    }
  }
  return index;
}

std::map<std::string, Figure> flatten_metrics_json(const std::string& text, const std::string& file) {
  const ordered_json j = parse_json(text, file);
  if (!j.is_object()) throw input_error(file, 0, "expected a JSON object");
  std::map<std::string, Figure> out;
  for (const auto& [group, figures] : j.items()) {
    if (!figures.is_object()) continue;
    for (const auto& [key, v] : figures.items()) out[group + "." + key] = figure_at(figures, key.c_str());
  }
  return out;
}

const std::vector<std::string>& metrics_keys() {
  // The writer's own layout: every key of metrics.json, even those that are null here.
  static const std::vector<std::string> keys = flatten_keys(metrics_json(Metrics{}));
  return keys;
}

}  // namespace tsgraphs::eval
