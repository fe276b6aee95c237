// A small command-line parser: each subcommand declares its options once (name, whether it takes a value,
// help text); anything else is a UsageError with a one-line message.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vct {

struct Option {
    std::string name;       // without the leading "--"
    std::string valueName;  // empty: a switch without a value
    std::string help;
    std::string defaultValue;
};

class ParsedArgs {
  public:
    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::string get(const std::string& name) const;  // the value given, else the option's default
    uint32_t getUint(const std::string& name, uint32_t min, uint32_t max) const;
    float getFloat(const std::string& name, float min, float max) const;
    // "WxH", each in [1, maxDimension].
    std::pair<uint32_t, uint32_t> getSize(const std::string& name, uint32_t maxDimension) const;

  private:
    friend class CommandSpec;
    std::map<std::string, std::string> values_;
    std::map<std::string, std::string> defaults_;
};

class CommandSpec {
  public:
    CommandSpec(std::string name, std::string summary, std::vector<Option> options);
    // Parses argv[first..]; "--help" returns nullopt after printing help to stdout.
    std::optional<ParsedArgs> parse(int argc, char** argv, int first) const;
    std::string help() const;
    const std::string& name() const { return name_; }
    const std::string& summary() const { return summary_; }

  private:
    std::string name_, summary_;
    std::vector<Option> options_;
};

}  // namespace vct
