#pragma once
// Records: ordered key/value lists of one measurement, passed from a child run to the parent
// as "key\tvalue" lines and written to the JSON report.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rbm::benchmark {

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct Value {
    enum class Kind { number, text, boolean } kind = Kind::number;
    double number = nan;
    std::string text;
    bool flag = false;
};

class Record {
public:
    void set(const std::string& key, double number) { slot(key) = Value{Value::Kind::number, number, {}, false}; }
    void set(const std::string& key, const std::string& text) { slot(key) = Value{Value::Kind::text, nan, text, false}; }
    void set(const std::string& key, const char* text) { set(key, std::string(text)); }
    void setFlag(const std::string& key, bool flag) { slot(key) = Value{Value::Kind::boolean, nan, {}, flag}; }

    bool has(const std::string& key) const { return find(key) != nullptr; }
    double number(const std::string& key) const
    {
        const Value* value = find(key);
        return value && value->kind == Value::Kind::number ? value->number : nan;
    }
    std::string text(const std::string& key) const
    {
        const Value* value = find(key);
        if (!value) return {};
        if (value->kind == Value::Kind::boolean) return value->flag ? "true" : "false";
        return value->text;
    }
    bool flag(const std::string& key) const
    {
        const Value* value = find(key);
        return value && value->kind == Value::Kind::boolean && value->flag;
    }
    void merge(const Record& other)
    {
        for (const auto& [key, value] : other.fields_) slot(key) = value;
    }

    std::string toLines() const
    {
        std::ostringstream out;
        out << std::setprecision(17);
        for (const auto& [key, value] : fields_) {
            out << key << '\t';
            switch (value.kind) {
            case Value::Kind::number: out << 'n' << value.number; break;
            case Value::Kind::boolean: out << 'b' << (value.flag ? 1 : 0); break;
            case Value::Kind::text: {
                std::string text = value.text;
                std::replace(text.begin(), text.end(), '\n', ' ');
                std::replace(text.begin(), text.end(), '\t', ' ');
                out << 's' << text;
                break;
            }
            }
            out << '\n';
        }
        return out.str();
    }

    static Record fromLines(const std::string& text)
    {
        Record record;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            const std::size_t tab = line.find('\t');
            if (tab == std::string::npos || tab + 1 >= line.size()) continue;
            const std::string key = line.substr(0, tab);
            const char kind = line[tab + 1];
            const std::string rest = line.substr(tab + 2);
            if (kind == 'n') record.set(key, std::strtod(rest.c_str(), nullptr));
            else if (kind == 'b') record.setFlag(key, rest == "1");
            else record.set(key, rest);
        }
        return record;
    }

    std::string toJson(const std::string& indent) const
    {
        std::ostringstream out;
        out << "{";
        bool first = true;
        for (const auto& [key, value] : fields_) {
            out << (first ? "\n" : ",\n") << indent << "  " << quoted(key) << ": ";
            first = false;
            switch (value.kind) {
            case Value::Kind::number:
                if (std::isfinite(value.number)) out << std::setprecision(6) << value.number;
                else out << "null";
                break;
            case Value::Kind::boolean: out << (value.flag ? "true" : "false"); break;
            case Value::Kind::text: out << quoted(value.text); break;
            }
        }
        out << (first ? "}" : "\n" + indent + "}");
        return out.str();
    }

    static std::string quoted(const std::string& text)
    {
        std::string out = "\"";
        for (char c : text) {
            if (c == '"' || c == '\\') out += '\\';
            if (static_cast<unsigned char>(c) < 0x20) {
                out += ' ';
                continue;
            }
            out += c;
        }
        return out + "\"";
    }

private:
    Value& slot(const std::string& key)
    {
        for (auto& [name, value] : fields_)
            if (name == key) return value;
        fields_.emplace_back(key, Value{});
        return fields_.back().second;
    }
    const Value* find(const std::string& key) const
    {
        for (const auto& [name, value] : fields_)
            if (name == key) return &value;
        return nullptr;
    }

    std::vector<std::pair<std::string, Value>> fields_;
};

std::string jsonArray(const std::vector<Record>& records, const std::string& indent);

std::optional<Record> recordFromOutput(const std::string& output);

} // namespace rbm::benchmark
