#include "app/bench/bench_table.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <fstream>

#include <unistd.h>

#include "app/cli/number_format.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

const BenchValue kNotMeasured{};

/// The shortest text that reads back as the same double; without an exponent for
/// magnitudes a spreadsheet shows plainly (0.0007, not 7e-04).
std::string exactNumber(double value) {
  char buffer[400];  // room for any double in fixed notation
  const double magnitude = std::fabs(value);
  const bool plain = std::isfinite(value) && magnitude >= 1e-6 && magnitude < 1e15;
  const auto [end, ec] = plain
                             ? std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed)
                             : std::to_chars(buffer, buffer + sizeof buffer, value);
  assert(ec == std::errc());
  return std::string(buffer, end);
}

std::string shown(const BenchValue& value, const BenchColumn& column) {
  if (std::holds_alternative<std::monostate>(value)) return "-";
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  const double number = std::holds_alternative<std::int64_t>(value)
                            ? static_cast<double>(std::get<std::int64_t>(value))
                            : std::get<double>(value);
  if (!std::isfinite(number)) return exactNumber(number);
  switch (column.style) {
    case BenchStyle::Count:
      if (const auto* count = std::get_if<std::int64_t>(&value); count && *count >= 0) {
        return withCommas(static_cast<std::uint64_t>(*count));
      }
      return fixed(number, 0);
    case BenchStyle::Scientific:
      return scientific(number, 3);
    case BenchStyle::Millimetres:
      return fixed(number * 1e3, column.decimals);
    case BenchStyle::Fixed:
    case BenchStyle::Text:
      break;
  }
  return std::holds_alternative<std::int64_t>(value) ? std::to_string(std::get<std::int64_t>(value))
                                                     : fixed(number, column.decimals);
}

std::string csvField(const BenchValue& value) {
  if (std::holds_alternative<std::monostate>(value)) return "";
  if (const auto* count = std::get_if<std::int64_t>(&value)) return std::to_string(*count);
  if (const auto* number = std::get_if<double>(&value)) return exactNumber(*number);
  const std::string& text = std::get<std::string>(value);
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted.push_back('"');
    quoted.push_back(c);
  }
  return quoted + "\"";
}

}  // namespace

BenchTable::BenchTable(std::string benchmark, std::vector<BenchColumn> columns)
    : benchmark_(std::move(benchmark)), columns_(std::move(columns)) {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) assert(columns_[i].key != columns_[j].key && "duplicate column key");
  }
}

std::size_t BenchTable::addRow() {
  rows_.emplace_back(columns_.size());
  return rows_.size() - 1;
}

std::size_t BenchTable::columnIndex(std::string_view key) const {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i].key == key) return i;
  }
  return columns_.size();
}

void BenchTable::set(std::size_t row, std::string_view key, BenchValue value) {
  const std::size_t column = columnIndex(key);
  assert(row < rows_.size() && column < columns_.size() && "no such row or column");
  rows_[row][column] = std::move(value);
}

const BenchValue& BenchTable::at(std::size_t row, std::string_view key) const {
  const std::size_t column = columnIndex(key);
  if (row >= rows_.size() || column >= columns_.size()) return kNotMeasured;
  return rows_[row][column];
}

nlohmann::ordered_json benchJson(const BenchTable& table) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < table.rowCount(); ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::object();
    for (const BenchColumn& column : table.columns()) {
      std::visit(
          [&](const auto& v) {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) {
              row[column.key] = nullptr;
            } else {
              row[column.key] = v;
            }
          },
          table.at(r, column.key));
    }
    rows.push_back(std::move(row));
  }
  nlohmann::ordered_json doc = {{"benchmark", table.benchmark()}, {"rows", std::move(rows)}};
  for (const auto& [key, value] : table.extra.items()) doc[key] = value;
  return doc;
}

void writeBenchText(std::ostream& out, const BenchTable& table) {
  const std::vector<BenchColumn>& columns = table.columns();
  std::vector<std::vector<std::string>> cells(table.rowCount());
  std::vector<std::size_t> widths(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) widths[c] = columns[c].heading.size();
  for (std::size_t r = 0; r < table.rowCount(); ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      cells[r].push_back(shown(table.at(r, columns[c].key), columns[c]));
      widths[c] = std::max(widths[c], cells[r].back().size());
    }
  }
  auto line = [&](const auto& textOf) {
    std::string text;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string cell = textOf(c);
      const std::string pad(widths[c] - std::min(widths[c], cell.size()), ' ');
      text += (c == 0 ? "" : "  ") + (columns[c].style == BenchStyle::Text ? cell + pad : pad + cell);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << '\n';
  };
  line([&](std::size_t c) { return columns[c].heading; });
  line([&](std::size_t c) { return std::string(widths[c], '-'); });
  for (std::size_t r = 0; r < table.rowCount(); ++r) line([&](std::size_t c) { return cells[r][c]; });
}

void writeBenchCsv(std::ostream& out, const BenchTable& table) {
  const std::vector<BenchColumn>& columns = table.columns();
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c == 0 ? "" : ",") << columns[c].key;
  out << '\n';
  for (std::size_t r = 0; r < table.rowCount(); ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      out << (c == 0 ? "" : ",") << csvField(table.at(r, columns[c].key));
    }
    out << '\n';
  }
}

void writeTextFileAtomically(const std::filesystem::path& file, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path temporary = file.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
    if (!stream)
      throw Error(file.string() + ": cannot be written (cannot create " + temporary.string() + ")");
    stream << text;
    stream.close();
    if (!stream) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw Error(file.string() + ": cannot be written (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temporary, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw Error(file.string() + ": cannot be written: " + ec.message());
  }
}

}  // namespace voxhap::cli
