// The matrix's static HTML report: index.html beside the cell folders, no network needed. Per
// scene: the reference, an SVG plot of SSIM against ms with the Pareto front marked and listed,
// and a table of every cell (its image, heat and leak maps, figures), sortable by any column,
// with the best cell of each technique highlighted. On load the page checks that every image
// loaded and records it on <body> (data-images-total, data-images-loaded), which the tests read
// through headless Chromium.
#pragma once

#include "gi/matrix/matrix.h"

#include <string>
#include <vector>

namespace gi::matrix {

std::string reportHTML(const std::string& title, const std::vector<CellResult>& results);

// The SVG plot of one scene's ok cells: SSIM against ms, one colour per technique, the front
// joined by a line. Log-scaled ms when the cells span more than 20x.
std::string paretoSVG(const std::vector<CellResult>& results, CostAxis axis = CostAxis::Frame);

// Writes results.csv, results.json and index.html into `dir` (atomically each).
void writeResults(const std::filesystem::path& dir, const std::string& title, const std::vector<CellResult>& results);

}  // namespace gi::matrix
