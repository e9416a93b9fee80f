// Line charts drawn by matplotlib (the project's one charting dependency, python3-matplotlib),
// fed with a long-format CSV: panel, series, x, y.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace plumage {

struct LineChart {
  struct Point {
    std::string panel;
    std::string series;
    double x = 0, y = 0;
    bool dashed = false;  // drawn dashed (a measurement beside predictions)
  };
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Point> points;
};

// Writes `png` atomically; throws plumage::Error if python3 or matplotlib is missing or fails.
void draw_line_chart(const LineChart& chart, const std::filesystem::path& png);

// Runs share/plumage/<script> with `inputs` (data files), the PNG to write, and `--title`;
// the PNG is written under a temporary name and renamed only on success.
void draw_script_chart(const std::string& script, const std::vector<std::string>& inputs,
                       const std::filesystem::path& png, const std::string& title,
                       const std::vector<std::string>& extra_args = {});

}  // namespace plumage
