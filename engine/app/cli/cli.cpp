#include "app/cli/cli.h"

#include <charconv>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "render/setting_table.h"

namespace vct {

std::string ParsedArgs::get(const std::string& name) const {
    if (auto it = values_.find(name); it != values_.end()) return it->second;
    if (auto it = defaults_.find(name); it != defaults_.end()) return it->second;
    return {};
}

uint32_t ParsedArgs::getUint(const std::string& name, uint32_t min, uint32_t max) const {
    const std::string text = get(name);
    uint64_t value = 0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < min || value > max)
        throw UsageError("--" + name + " '" + text + "': expected an integer from " + std::to_string(min) +
                         " to " + std::to_string(max));
    return uint32_t(value);
}

float ParsedArgs::getFloat(const std::string& name, float min, float max) const {
    return parseNumber(get(name), "--" + name, min, max);
}

std::pair<uint32_t, uint32_t> ParsedArgs::getSize(const std::string& name, uint32_t maxDimension) const {
    return parseSize(get(name), "--" + name, maxDimension);
}

CommandSpec::CommandSpec(std::string name, std::string summary, std::vector<Option> options)
    : name_(std::move(name)), summary_(std::move(summary)), options_(std::move(options)) {}

std::optional<ParsedArgs> CommandSpec::parse(int argc, char** argv, int first) const {
    ParsedArgs args;
    for (const Option& option : options_)
        if (!option.defaultValue.empty()) args.defaults_[option.name] = option.defaultValue;
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(help().c_str(), stdout);
            return std::nullopt;
        }
        if (arg.rfind("--", 0) != 0)
            throw UsageError("vct " + name_ + ": unexpected argument '" + arg + "' (see vct " + name_ +
                             " --help)");
        std::string key = arg.substr(2), value;
        bool inlineValue = false;
        if (size_t eq = key.find('='); eq != std::string::npos) {
            value = key.substr(eq + 1);
            key = key.substr(0, eq);
            inlineValue = true;
        }
        const Option* option = nullptr;
        for (const Option& candidate : options_)
            if (candidate.name == key) option = &candidate;
        if (!option)
            throw UsageError("vct " + name_ + ": unknown flag '--" + key + "' (see vct " + name_ +
                             " --help)");
        if (option->valueName.empty()) {
            if (inlineValue) throw UsageError("vct " + name_ + ": --" + key + " takes no value");
            args.values_[key] = "1";
            continue;
        }
        if (!inlineValue) {
            if (i + 1 >= argc)
                throw UsageError("vct " + name_ + ": --" + key + " needs a value (" + option->valueName +
                                 ")");
            value = argv[++i];
        }
        args.values_[key] = value;
    }
    return args;
}

std::string CommandSpec::help() const {
    std::ostringstream out;
    out << "usage: vct " << name_ << " [options]\n" << summary_ << "\n\noptions:\n";
    for (const Option& option : options_) {
        std::string flag = "  --" + option.name + (option.valueName.empty() ? "" : " " + option.valueName);
        out << flag << std::string(flag.size() < 28 ? 28 - flag.size() : 1, ' ') << option.help;
        if (!option.defaultValue.empty() && !option.valueName.empty())
            out << " (default " << option.defaultValue << ")";
        out << "\n";
    }
    out << "  --help                    this text\n";
    return out.str();
}

}  // namespace vct
