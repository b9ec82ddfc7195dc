#pragma once
/// The results of one `voxhap bench` benchmark: rows of named numeric or text
/// columns, written as an aligned text table (stdout by default), as one JSON
/// document (`--json`) or as CSV (`--csv FILE`). A benchmark only fills rows;
/// everything here is shared by all of them.
///
/// Keys are fixed at construction and keep their order in every format. JSON and
/// CSV carry values as measured (SI units, full precision); only the text table
/// rounds and rescales them (metres shown as mm, large counts as 4.59e8, …).

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace voxhap::cli {

/// One cell: not measured (monostate: JSON null, empty in CSV, "-" in the table),
/// a count, a real number or text.
using BenchValue = std::variant<std::monostate, std::int64_t, double, std::string>;

/// How the text table shows a column.
enum class BenchStyle {
  Text,         ///< as it is, left-aligned
  Count,        ///< integer with thousands separators: 23,960
  Scientific,   ///< 3 significant digits and a power of ten: 4.59e8
  Fixed,        ///< `decimals` digits after the point
  Millimetres,  ///< a length in metres shown in mm with `decimals` digits
};

struct BenchColumn {
  std::string key;      ///< JSON member and CSV header, snake_case with the unit: "voxel_size_m"
  std::string heading;  ///< text table heading: "voxel mm"
  BenchStyle style = BenchStyle::Fixed;
  int decimals = 2;  ///< for Fixed and Millimetres
};

class BenchTable {
public:
  /// A table for the benchmark called `benchmark` with these columns (unique keys).
  BenchTable(std::string benchmark, std::vector<BenchColumn> columns);

  /// Appends a row whose cells are all "not measured"; returns its index.
  std::size_t addRow();
  /// Sets one cell. `key` must be one of the columns (a programmer error otherwise).
  void set(std::size_t row, std::string_view key, BenchValue value);
  /// The cell, or monostate when `key` is not a column.
  const BenchValue& at(std::size_t row, std::string_view key) const;
  /// The column index of `key`, or columns().size() when there is none.
  std::size_t columnIndex(std::string_view key) const;

  const std::string& benchmark() const { return benchmark_; }
  const std::vector<BenchColumn>& columns() const { return columns_; }
  std::size_t rowCount() const { return rows_.size(); }

  /// Members added to the JSON document after "benchmark" and "rows" (settings, notes).
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();

private:
  std::string benchmark_;
  std::vector<BenchColumn> columns_;
  std::vector<std::vector<BenchValue>> rows_;
};

/// `{"benchmark": NAME, "rows": [{key: value, …}, …], …extra}`.
nlohmann::ordered_json benchJson(const BenchTable& table);

/// An aligned table: a heading line, a rule, one line per row; numbers right-aligned.
void writeBenchText(std::ostream& out, const BenchTable& table);

/// A header line of the keys, then one line per row; numbers at full precision, text
/// quoted when it holds a comma, quote or line break (RFC 4180), lines ending in "\n".
void writeBenchCsv(std::ostream& out, const BenchTable& table);

/// Writes `text` to `file` through a temporary file renamed into place, so that a
/// failure never leaves a partial file. Throws voxhap::Error naming the file.
void writeTextFileAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace voxhap::cli
