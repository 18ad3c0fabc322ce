// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A benchmark's table as results, for the C++ programs: NAME.json (the rows, the command, the
// machine, the date) and NAME.md (the same as a Markdown table under one header line), as
// bench/bench_results.py writes them for the Python scripts; bench/make_benchmarks_page.py
// builds docs/benchmarks.md from them and checks that each .md is what the Python renderer
// makes of its .json, so the two writers cannot drift apart.
//
//   hyvox::bench::ResultTable table("mesh_to_volume", "hyvox cpu against OpenVDB",
//                                   {{"mesh"}, {"res"}, {"stage ms", 1}}, argc, argv);
//   table.add({name, resolution, stage_ms});
//   table.write(out_dir);  // default: HYVOX_BENCH_RESULTS_DIR (bench/results/)
#include <sys/utsname.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include "hyvox/json_text.h"
#include "hyvox/version.h"

namespace hyvox::bench {

struct ResultColumn {
    std::string name;
    int digits = -1;  // digits after the point for numbers with a fraction; -1: the renderer's default (2)
};

// One value of a row: text, a whole number, a real, or nothing ("-").
struct Cell {
    std::variant<std::monostate, std::string, std::int64_t, double> value;
    Cell() = default;
    Cell(const char* text) : value(std::string(text)) {}
    Cell(std::string text) : value(std::move(text)) {}
    template <typename T, typename = std::enable_if_t<std::is_integral_v<T>>>
    Cell(T number) : value(std::int64_t(number)) {}
    Cell(double number) {
        if (std::isfinite(number)) value = number;  // NaN and infinities: not measured
    }
};

namespace detail {

// The shortest text that reads back as the same double (what Python's json writes).
inline std::string jsonNumber(double value) {
    char buf[32];
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, value);
        if (std::strtod(buf, nullptr) == value) break;
    }
    std::string text = buf;
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // stays a real for Python
    return text;
}

// `value` rounded to `digits` decimals as a decimal reads it (Python's round()).
inline double rounded(double value, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, value);
    return std::strtod(buf, nullptr);
}

// "1234567" -> "1,234,567" (the digits before the point; a leading '-' kept).
inline std::string withThousands(const std::string& digits) {
    const std::size_t start = digits[0] == '-' ? 1 : 0;
    std::string out = digits.substr(0, start);
    const std::string body = digits.substr(start);
    for (std::size_t i = 0; i < body.size(); ++i) {
        if (i && (body.size() - i) % 3 == 0) out += ',';
        out += body[i];
    }
    return out;
}

// A cell as bench_results.py's _cell writes it.
inline std::string markdownCell(const Cell& cell, int digits) {
    if (const auto* text = std::get_if<std::string>(&cell.value)) {
        std::string out;
        for (const char c : *text) out += c == '|' ? std::string("\\|") : std::string(1, c);
        return out;
    }
    if (const auto* whole = std::get_if<std::int64_t>(&cell.value)) {
        const std::string text = std::to_string(*whole);
        return std::llabs(*whole) >= 10000 ? withThousands(text) : text;
    }
    if (const auto* real = std::get_if<double>(&cell.value)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*f", digits >= 0 ? digits : 2, *real);
        const std::string text = buf;
        const std::size_t point = text.find('.');
        return withThousands(text.substr(0, point)) + (point == std::string::npos ? "" : text.substr(point));
    }
    return "-";
}

inline std::string firstLineValue(const char* path, const std::string& key, char separator) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (line.compare(0, key.size(), key) == 0) {
            std::string value = line.substr(line.find(separator) + 1);
            const std::size_t begin = value.find_first_not_of(" \t\"");
            const std::size_t end = value.find_last_not_of(" \t\"");
            return begin == std::string::npos ? "" : value.substr(begin, end - begin + 1);
        }
    return "";
}

inline std::string commandOutput(const std::string& command) {
    std::string out;
    if (std::FILE* pipe = ::popen(command.c_str(), "r")) {
        char buf[256];
        while (std::fgets(buf, sizeof buf, pipe)) out += buf;
        if (::pclose(pipe) != 0) return "";
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
}

// Python's shlex.quote.
inline std::string shellQuote(const std::string& word) {
    if (word.empty()) return "''";
    bool safe = true;
    for (const char c : word)
        safe = safe &&
            (std::isalnum(static_cast<unsigned char>(c)) || std::string("@%+=:,./-_").find(c) != std::string::npos);
    if (safe) return word;
    std::string out = "'";
    for (const char c : word) out += c == '\'' ? std::string("'\"'\"'") : std::string(1, c);
    return out + "'";
}

inline double loadAverage() {
    double load[1] = {0};
    return ::getloadavg(load, 1) == 1 ? rounded(load[0], 2) : 0.0;
}

}  // namespace detail

class ResultTable {
public:
    ResultTable(std::string name, std::string title, std::vector<ResultColumn> columns, int argc, char** argv)
        : name_(std::move(name)), title_(std::move(title)), columns_(std::move(columns)) {
        const std::string root = HYVOX_SOURCE_DIR;
        for (int a = 0; a < argc; ++a) {
            std::string word = argv[a];
            if (a == 0) {
                std::error_code error;
                const std::filesystem::path absolute = std::filesystem::weakly_canonical(word, error);
                const std::string text = absolute.string();
                if (!error && text.compare(0, root.size() + 1, root + "/") == 0) word = text.substr(root.size() + 1);
            }
            command_ += (a ? " " : "") + detail::shellQuote(word);
        }
        load_start_ = detail::loadAverage();
        char stamp[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
        date_ = stamp;
    }

    void add(std::vector<Cell> row) {
        if (row.size() != columns_.size())
            throw std::logic_error(name_ + ": a row of " + std::to_string(row.size()) + " values for " +
                                   std::to_string(columns_.size()) + " columns");
        rows_.push_back(std::move(row));
    }
    void note(std::string text) { notes_.push_back(std::move(text)); }
    // The GL device the figures are from, for the header (the GL benchmarks).
    void setGpu(std::string gpu) { gpu_ = std::move(gpu); }

    // Writes DIR/NAME.json and DIR/NAME.md (each staged and renamed) and says where.
    void write(const std::string& dir) const {
        std::filesystem::create_directories(dir);
        const Machine m = machine();
        writeFile(dir + "/" + name_ + ".json", json(m));
        writeFile(dir + "/" + name_ + ".md", markdown(m));
        std::printf("results: %s/%s.json, .md\n", dir.c_str(), name_.c_str());
    }

private:
    struct Machine {
        std::string cpu, os, kernel, commit, version;
        unsigned cores = 0;
        double memory_gib = 0, load_start = 0, load_end = 0;
        bool dirty = false, quick = false;
    };

    Machine machine() const {
        Machine m;
        m.cpu = detail::firstLineValue("/proc/cpuinfo", "model name", ':');
        if (m.cpu.empty()) m.cpu = "unknown";
        m.cores = std::thread::hardware_concurrency();
        m.memory_gib = detail::rounded(
            std::atof(detail::firstLineValue("/proc/meminfo", "MemTotal", ':').c_str()) / (1024.0 * 1024.0), 1);
        m.os = detail::firstLineValue("/etc/os-release", "PRETTY_NAME", '=');
        utsname names{};
        if (::uname(&names) == 0) m.kernel = names.release;
        m.load_start = load_start_;
        m.load_end = detail::loadAverage();
        const std::string git = "git -C " + detail::shellQuote(HYVOX_SOURCE_DIR) + " ";
        m.commit = detail::commandOutput(git + "rev-parse --short=10 HEAD 2>/dev/null");
        // Local changes to the code, not to the results being written or the page made of them.
        m.dirty = !m.commit.empty() &&
            !detail::commandOutput(git +
                                   "status --porcelain --untracked-files=no -- . ':!bench/results' "
                                   "':!docs/benchmarks.md' 2>/dev/null")
                 .empty();
        m.version = hyvox::version();
        const char* quick = std::getenv("HYVOX_BENCH_QUICK");
        m.quick = quick && std::string(quick) == "1";
        return m;
    }

    std::string json(const Machine& m) const {
        using detail::jsonNumber;
        std::ostringstream out;
        out << "{\n \"benchmark\": " << jsonQuote(name_) << ",\n \"title\": " << jsonQuote(title_)
            << ",\n \"command\": " << jsonQuote(command_) << ",\n \"date\": " << jsonQuote(date_)
            << ",\n \"machine\": {\n  \"cpu\": " << jsonQuote(m.cpu) << ",\n  \"cores\": " << m.cores
            << ",\n  \"memory_gib\": " << jsonNumber(m.memory_gib) << ",\n  \"os\": " << jsonQuote(m.os)
            << ",\n  \"kernel\": " << jsonQuote(m.kernel);
        if (!gpu_.empty()) out << ",\n  \"gpu\": " << jsonQuote(gpu_);
        out << ",\n  \"load_start\": " << jsonNumber(m.load_start) << ",\n  \"load_end\": " << jsonNumber(m.load_end)
            << "\n },\n \"hyvox\": {\n  \"version\": " << jsonQuote(m.version)
            << ",\n  \"commit\": " << jsonQuote(m.commit) << ",\n  \"dirty\": " << (m.dirty ? "true" : "false")
            << "\n },\n \"quick\": " << (m.quick ? "true" : "false") << ",\n \"columns\": [";
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            out << (c ? ",\n  " : "\n  ") << "{\"name\": " << jsonQuote(columns_[c].name);
            if (columns_[c].digits >= 0) out << ", \"digits\": " << columns_[c].digits;
            out << "}";
        }
        out << "\n ],\n \"rows\": [";
        for (std::size_t r = 0; r < rows_.size(); ++r) {
            out << (r ? ",\n  [" : "\n  [");
            for (std::size_t c = 0; c < rows_[r].size(); ++c) {
                const auto& v = rows_[r][c].value;
                out << (c ? ", " : "");
                if (const auto* text = std::get_if<std::string>(&v))
                    out << jsonQuote(*text);
                else if (const auto* whole = std::get_if<std::int64_t>(&v))
                    out << *whole;
                else if (const auto* real = std::get_if<double>(&v))
                    out << jsonNumber(*real);
                else
                    out << "null";
            }
            out << "]";
        }
        out << "\n ],\n \"notes\": [";
        for (std::size_t n = 0; n < notes_.size(); ++n) out << (n ? ",\n  " : "\n  ") << jsonQuote(notes_[n]);
        out << (notes_.empty() ? "]\n}\n" : "\n ]\n}\n");
        return out.str();
    }

    // bench_results.py's render_markdown, line for line.
    std::string markdown(const Machine& m) const {
        char load[64], memory[32];
        std::snprintf(load, sizeof load, "load %.1f-%.1f", m.load_start, m.load_end);
        std::snprintf(memory, sizeof memory, "%s GiB", detail::jsonNumber(m.memory_gib).c_str());
        std::string what;
        const std::string cores = m.cores ? std::to_string(m.cores) + " cores" : "";
        for (const std::string& part :
             {m.cpu, cores, m.memory_gib > 0 ? std::string(memory) : std::string(), m.os, gpu_, std::string(load)})
            if (!part.empty()) what += (what.empty() ? "" : ", ") + part;
        // The date and the commit stay in the .json: the page shows the current results, git
        // their history.
        std::ostringstream out;
        out << "<!-- Generated by the benchmark named below; bench/make_benchmarks_page.py puts it in "
               "docs/benchmarks.md. -->\n\n### "
            << title_ << "\n\n`" << command_ << "`  \n"
            << what << "; hyvox " << m.version << ".\n";
        if (m.quick)
            out << "\n*A quick run at small sizes (`bench/run_all.sh --quick`): it shows that the benchmark works, "
                   "not figures to quote.*\n";
        out << "\n|";
        for (const ResultColumn& c : columns_) out << " " << c.name << " |";
        out << "\n|";
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            bool numeric = false, other = false;
            for (const auto& row : rows_) {
                const auto& v = row[c].value;
                if (std::holds_alternative<std::int64_t>(v) || std::holds_alternative<double>(v))
                    numeric = true;
                else if (std::holds_alternative<std::string>(v))
                    other = true;
            }
            out << (numeric && !other ? "---:|" : "---|");
        }
        out << "\n";
        for (const auto& row : rows_) {
            out << "|";
            for (std::size_t c = 0; c < row.size(); ++c)
                out << " " << detail::markdownCell(row[c], columns_[c].digits) << " |";
            out << "\n";
        }
        if (!notes_.empty()) {
            out << "\n";
            for (const std::string& n : notes_) out << n << "\n";
        }
        return out.str();
    }

    static void writeFile(const std::string& path, const std::string& text) {
        const std::string staged = path + ".tmp";
        {
            std::ofstream out(staged, std::ios::binary);
            out << text;
            if (!out.flush()) throw std::runtime_error("cannot write " + staged);
        }
        std::filesystem::rename(staged, path);
    }

    std::string name_, title_, command_, date_, gpu_;
    std::vector<ResultColumn> columns_;
    std::vector<std::vector<Cell>> rows_;
    std::vector<std::string> notes_;
    double load_start_ = 0;
};

}  // namespace hyvox::bench
