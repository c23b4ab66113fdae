#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <string>
#include <type_traits>

#include "tsgraphs/core/config_fields.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

namespace tsgraphs::pipeline {
namespace {

using detail::IsOptional;

// A number as both files write it: a float keeps a '.', so that it reads back as one.
std::string number_text(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Emits each visited field as YAML (the run folder's params.yaml).
struct Writer {
  YAML::Emitter& out;

  template <class T>
  void value(const T& field) {
    if constexpr (IsOptional<T>::value) {
      if (field) {
        value(*field);
      } else {
        out << kAutoWord;
      }
    } else if constexpr (std::is_floating_point_v<T>) {
      out << number_text(field);
    } else {
      out << field;
    }
  }
  template <class T>
  void operator()(const char* key, const T& field, const char*) {
    out << YAML::Key << key << YAML::Value;
    value(field);
  }
  template <class T, class L>
  void operator()(const char* key, const T& field, const L& limits, const char*) {
    out << YAML::Key << key << YAML::Value;
    if constexpr (std::is_enum_v<T>) {
      out << limits.name(field);
    } else {
      value(field);
    }
  }
  template <class S>
  void section(const char* key, S& sub, const char*) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    sub.visit(*this);
    out << YAML::EndMap;
  }
  void require(bool, const char*, const std::string&) {}
};

// Writes each visited field as a line of config/params.yaml: the key, its value and its
// comment, the comments in one column where the lines are short enough.
struct DocumentedWriter {
  std::string& out;
  std::string indent;

  static constexpr std::size_t kCommentColumn = 30;

  void line(const std::string& text, const char* comment) {
    out += text;
    out += text.size() < kCommentColumn ? std::string(kCommentColumn - text.size(), ' ') : "  ";
    out += std::string("# ") + comment + "\n";
  }
  template <class T>
  static std::string text(const T& field) {
    if constexpr (IsOptional<T>::value) {
      return field ? text(*field) : kAutoWord;
    } else if constexpr (std::is_same_v<T, bool>) {
      return field ? "true" : "false";
    } else if constexpr (std::is_floating_point_v<T>) {
      return number_text(field);
    } else if constexpr (std::is_same_v<T, std::string>) {
      return field;
    } else {
      return std::to_string(field);
    }
  }
  template <class T>
  void operator()(const char* key, const T& field, const char* comment) {
    line(indent + key + ": " + text(field), comment);
  }
  template <class T, class L>
  void operator()(const char* key, const T& field, const L& limits, const char* comment) {
    if constexpr (std::is_enum_v<T>) {
      line(indent + key + ": " + limits.name(field), comment);
    } else {
      (*this)(key, field, comment);
    }
  }
  template <class S>
  void section(const char* key, S& sub, const char* comment) {
    if (indent.empty() && !out.empty()) out += "\n";
    line(indent + key + ":", comment);
    DocumentedWriter inner{out, indent + "  "};
    sub.visit(inner);
  }
  void require(bool, const char*, const std::string&) {}
};

constexpr const char* kParamsHeader =
    "# tsgraphs parameters: every key with its default and what it does. Pass a copy with your\n"
    "# changes to `tsgraphs run SEQ_DIR --out RUN_DIR --config params.yaml`; keys you leave out\n"
    "# keep these defaults, unknown keys are an error, and so is a value outside a key's limits\n"
    "# (the error names the file, line, key and the limits). The run folder gets the parameters\n"
    "# actually used. Written by `tsgraphs params` from the fields' declarations in the code.\n\n";

}  // namespace

std::string dump_pipeline_config(const PipelineConfig& config) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  Writer writer{out};
  PipelineConfig copy = config;
  copy.visit(writer);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string documented_pipeline_config(const PipelineConfig& config) {
  std::string body;
  DocumentedWriter writer{body, ""};
  PipelineConfig copy = config;
  copy.visit(writer);
  return kParamsHeader + body;
}

}  // namespace tsgraphs::pipeline
