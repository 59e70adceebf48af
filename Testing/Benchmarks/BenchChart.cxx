// SPDX-License-Identifier: BSD-3-Clause
// The speed-versus-accuracy chart of docs/benchmarks.md, drawn with VTK's charts (vtkChartXY in
// a vtkContextActor, rendered offscreen: run it under Testing/Rendering/RunHeadless.sh).
//
//   BenchChart [--out DIR] [--surface NAME] [--resolution N]
//
// Reads DIR/filter.tsv, DIR/accuracy.tsv and DIR/rendering.tsv (written by BenchTangentFrames,
// BenchTangentAccuracy and BenchNormalMapRendering) and writes DIR/benchmarks.png: two panels,
// both axes logarithmic, every point labelled, the Pareto front (the points no other point
// beats on both axes) joined by a dashed line.
// - Left: the tangent filters. x: throughput on the float torus nearest to 1 million
//   triangles, one thread (higher is better); y: mean angle to the analytic tangent on the
//   wavy surface at the middle resolution (--surface, --resolution; lower is better). The floor
//   (no tangents computed) is a vertical line.
// - Right: the mappers. x: ms per frame (lower is better); y: mean channel error against the
//   displaced geometry under the same lighting model (lower is better).
#include "BenchCommon.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContext2D.h"
#include "vtkContextActor.h"
#include "vtkContextItem.h"
#include "vtkContextScene.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageAppend.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/// A tab-separated file as rows of named fields (the header line gives the names).
std::vector<std::map<std::string, std::string>> ReadTable(const std::string& path)
{
  std::vector<std::map<std::string, std::string>> rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> names;
  const auto split = [](const std::string& text)
  {
    std::vector<std::string> fields;
    std::stringstream s(text);
    for (std::string field; std::getline(s, field, '\t');)
    {
      fields.push_back(field);
    }
    return fields;
  };
  if (std::getline(in, line))
  {
    names = split(line);
  }
  while (std::getline(in, line))
  {
    const auto fields = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < names.size() && i < fields.size(); ++i)
    {
      row[names[i]] = fields[i];
    }
    rows.push_back(row);
  }
  return rows;
}

double Number(const std::map<std::string, std::string>& row, const std::string& key)
{
  const auto it = row.find(key);
  return it == row.end() ? 0.0 : std::atof(it->second.c_str());
}

struct Point
{
  std::string Label;
  double X, Y; // data values (the chart shows log10 of them)
  bool Ours;
  std::string Group; // one Pareto front per group (the lighting model); empty: one front
};

/**
 * Draws each point's label beside it: to the right at the point's height if that space is free
 * (of other labels and markers, inside the plot), else the nearest free place above or below,
 * to the right or the left, joined to its point by a thin line.
 */
class PointLabels : public vtkContextItem
{
public:
  static PointLabels* New() { VTK_STANDARD_NEW_BODY(PointLabels); }
  vtkTypeMacro(PointLabels, vtkContextItem);
  vtkChartXY* Chart = nullptr;
  std::vector<Point> Points; // X and Y already in log10

  bool Paint(vtkContext2D* painter) override
  {
    vtkAxis* xAxis = this->Chart->GetAxis(vtkAxis::BOTTOM);
    vtkAxis* yAxis = this->Chart->GetAxis(vtkAxis::LEFT);
    const auto screen = [](vtkAxis* axis, int k, double value)
    {
      const double t = (value - axis->GetMinimum()) / (axis->GetMaximum() - axis->GetMinimum());
      return static_cast<float>(
        axis->GetPoint1()[k] + t * (axis->GetPoint2()[k] - axis->GetPoint1()[k]));
    };
    const float plot[4] = {
      xAxis->GetPoint1()[0], yAxis->GetPoint1()[1], xAxis->GetPoint2()[0], yAxis->GetPoint2()[1]
    };
    painter->GetTextProp()->SetFontSize(13);
    painter->GetTextProp()->SetColor(0.1, 0.1, 0.1);
    painter->GetTextProp()->SetJustificationToLeft();
    painter->GetTextProp()->SetVerticalJustificationToCentered();
    painter->GetPen()->SetColor(150, 150, 150, 255);
    painter->GetPen()->SetWidth(1.0f);
    using Box = std::array<float, 4>; // x0, y0, x1, y1
    std::vector<Box> taken;
    std::vector<std::array<float, 2>> at;
    for (const Point& p : this->Points)
    {
      at.push_back({ screen(xAxis, 0, p.X), screen(yAxis, 1, p.Y) });
      taken.push_back({ at.back()[0] - 7, at.back()[1] - 7, at.back()[0] + 7, at.back()[1] + 7 });
    }
    const auto free = [&](const Box& b)
    {
      if (b[0] < plot[0] || b[2] > plot[2] || b[1] < plot[1] || b[3] > plot[3])
      {
        return false;
      }
      for (const Box& t : taken)
      {
        if (b[0] < t[2] && b[2] > t[0] && b[1] < t[3] && b[3] > t[1])
        {
          return false;
        }
      }
      return true;
    };
    for (size_t i = 0; i < this->Points.size(); ++i)
    {
      float bounds[4];
      painter->ComputeStringBounds(this->Points[i].Label, bounds);
      const float w = bounds[2], h = bounds[3] + 2.0f;
      Box chosen{ at[i][0] + 9, at[i][1] - h / 2, at[i][0] + 9 + w, at[i][1] + h / 2 };
      bool found = false;
      for (int step = 0; step < 12 && !found; ++step)
      {
        const float dy = (step % 2 ? -1.0f : 1.0f) * ((step + 1) / 2) * h;
        for (float side : { 1.0f, -1.0f })
        {
          const float x0 = side > 0 ? at[i][0] + 9 : at[i][0] - 9 - w;
          const Box b{ x0, at[i][1] + dy - h / 2, x0 + w, at[i][1] + dy + h / 2 };
          if (!found && free(b))
          {
            chosen = b;
            found = true;
          }
        }
      }
      taken.push_back(chosen);
      const float cy = 0.5f * (chosen[1] + chosen[3]);
      if (std::abs(cy - at[i][1]) > 1.0f)
      {
        const float edge = chosen[0] > at[i][0] ? chosen[0] - 2 : chosen[2] + 2;
        painter->DrawLine(at[i][0], at[i][1], edge, cy);
      }
      painter->DrawString(chosen[0], cy, this->Points[i].Label);
    }
    return true;
  }
};

/// Decade ticks (and 2x, 3x, 5x between them) with plain-number labels, over [lo, hi] in log10.
void LogAxis(vtkAxis* axis, double lo, double hi, const std::string& title)
{
  vtkNew<vtkDoubleArray> positions;
  vtkNew<vtkStringArray> labels;
  for (int decade = static_cast<int>(std::floor(lo)); decade <= static_cast<int>(std::ceil(hi));
       ++decade)
  {
    for (double mantissa : { 1.0, 2.0, 3.0, 5.0 })
    {
      const double position = decade + std::log10(mantissa);
      if (position >= lo && position <= hi)
      {
        std::ostringstream text;
        text << mantissa * std::pow(10.0, decade);
        positions->InsertNextValue(position);
        labels->InsertNextValue(text.str());
      }
    }
  }
  axis->SetCustomTickPositions(positions, labels);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(lo, hi);
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(14);
  axis->GetLabelProperties()->SetFontSize(12);
}

vtkSmartPointer<vtkTable> Table(const std::vector<std::pair<double, double>>& xy)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkFloatArray> x, y;
  x->SetName("x");
  y->SetName("y");
  table->AddColumn(x);
  table->AddColumn(y);
  table->SetNumberOfRows(static_cast<vtkIdType>(xy.size()));
  for (size_t i = 0; i < xy.size(); ++i)
  {
    table->SetValue(static_cast<vtkIdType>(i), 0, xy[i].first);
    table->SetValue(static_cast<vtkIdType>(i), 1, xy[i].second);
  }
  return table;
}

/**
 * One panel: the points (log10 of both coordinates), their labels and their Pareto front;
 * higherXIsBetter for throughput, false for time. `verticalLine` > 0: a labelled vertical line
 * at that x (the floor).
 */
vtkSmartPointer<vtkRenderWindow> Panel(const std::string& title,
  std::vector<Point> points,
  bool higherXIsBetter,
  const std::string& xTitle,
  const std::string& yTitle,
  double verticalLine,
  const std::string& verticalLabel)
{
  // A context actor in a plain renderer: vtkContextView would do the same, but its module
  // (ViewsContext2D) pulls in VTK's widgets and volume rendering.
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(760, 560);
  window->SetOffScreenRendering(1);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(renderer);
  vtkNew<vtkContextActor> actor;
  renderer->AddActor(actor);
  vtkNew<vtkChartXY> chart;
  actor->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);

  double xs[2] = { 1e300, -1e300 }, ys[2] = { 1e300, -1e300 };
  for (Point& p : points)
  {
    p.X = std::log10(std::max(p.X, 1e-6));
    p.Y = std::log10(std::max(p.Y, 1e-6));
    xs[0] = std::min(xs[0], p.X), xs[1] = std::max(xs[1], p.X);
    ys[0] = std::min(ys[0], p.Y), ys[1] = std::max(ys[1], p.Y);
  }
  if (verticalLine > 0)
  {
    xs[0] = std::min(xs[0], std::log10(verticalLine));
    xs[1] = std::max(xs[1], std::log10(verticalLine));
  }
  // Margins: a fifth of a decade below, and room for the labels to the right.
  const double xMargin = std::max(0.15, 0.08 * (xs[1] - xs[0]));
  const double yMargin = std::max(0.15, 0.08 * (ys[1] - ys[0]));
  const double xRange[2] = { xs[0] - xMargin, xs[1] + 2.5 * xMargin };
  const double yRange[2] = { ys[0] - yMargin, ys[1] + yMargin };

  // The Pareto front of each group: the points that no other point of the group beats on
  // both axes, in x order.
  std::vector<std::string> groups;
  for (const Point& p : points)
  {
    if (std::find(groups.begin(), groups.end(), p.Group) == groups.end())
    {
      groups.push_back(p.Group);
    }
  }
  for (size_t g = 0; g < groups.size(); ++g)
  {
    std::vector<std::pair<double, double>> front;
    for (const Point& p : points)
    {
      bool dominated = false;
      for (const Point& q : points)
      {
        const bool xNoWorse = higherXIsBetter ? q.X >= p.X : q.X <= p.X;
        const bool xBetter = higherXIsBetter ? q.X > p.X : q.X < p.X;
        dominated =
          dominated || (q.Group == p.Group && xNoWorse && q.Y <= p.Y && (xBetter || q.Y < p.Y));
      }
      if (!dominated && p.Group == groups[g])
      {
        front.emplace_back(p.X, p.Y);
      }
    }
    std::sort(front.begin(), front.end());
    if (front.size() > 1)
    {
      vtkPlot* frontLine = chart->AddPlot(vtkChart::LINE);
      frontLine->SetInputData(Table(front), 0, 1);
      const double grey = 0.45 + 0.2 * g;
      frontLine->SetColor(grey, grey, grey);
      frontLine->SetWidth(2.0);
      frontLine->GetPen()->SetLineType(g == 0 ? vtkPen::DASH_LINE : vtkPen::DASH_DOT_LINE);
      frontLine->SetLabel(
        groups[g].empty() ? std::string("Pareto front") : "Pareto front, " + groups[g]);
    }
  }

  if (verticalLine > 0)
  {
    const double x = std::log10(verticalLine);
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(Table({ { x, yRange[0] }, { x, yRange[1] } }), 0, 1);
    line->SetColor(0.8, 0.3, 0.1);
    line->SetWidth(1.5);
    line->GetPen()->SetLineType(vtkPen::DOT_LINE);
    line->SetLabel(verticalLabel);
  }
  const unsigned char ours[3] = { 31, 119, 180 }, theirs[3] = { 214, 39, 40 };
  bool oursInLegend = false, vtkInLegend = false;
  for (const Point& p : points)
  {
    auto* plot = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
    plot->SetInputData(Table({ { p.X, p.Y } }), 0, 1);
    const unsigned char* color = p.Ours ? ours : theirs;
    plot->SetColor(color[0], color[1], color[2], 255);
    plot->SetMarkerStyle(p.Ours ? vtkPlotPoints::CIRCLE : vtkPlotPoints::SQUARE);
    plot->SetMarkerSize(11.0);
    plot->SetLabel(p.Ours ? "ours" : "VTK");
    // One legend entry for each kind.
    plot->SetLegendVisibility(p.Ours ? !oursInLegend : !vtkInLegend);
    (p.Ours ? oursInLegend : vtkInLegend) = true;
  }
  LogAxis(chart->GetAxis(vtkAxis::BOTTOM), xRange[0], xRange[1], xTitle);
  LogAxis(chart->GetAxis(vtkAxis::LEFT), yRange[0], yRange[1], yTitle);

  vtkNew<PointLabels> labels;
  labels->Chart = chart;
  labels->Points = points;
  actor->GetScene()->AddItem(labels);
  window->Render();
  return window;
}
}

int main(int argc, char* argv[])
{
  std::string out = ".", surface = "wavy";
  int resolution = 0; // 0: the middle one of accuracy.tsv
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string arg = argv[i];
    if (arg == "--out")
    {
      out = argv[i + 1];
    }
    else if (arg == "--surface")
    {
      surface = argv[i + 1];
    }
    else if (arg == "--resolution")
    {
      resolution = std::atoi(argv[i + 1]);
    }
  }
  const auto filter = ReadTable(out + "/filter.tsv");
  const auto accuracy = ReadTable(out + "/accuracy.tsv");
  const auto rendering = ReadTable(out + "/rendering.tsv");
  if (filter.empty() || accuracy.empty() || rendering.empty())
  {
    std::cerr << "BenchChart: missing or empty filter.tsv, accuracy.tsv or rendering.tsv in " << out
              << std::endl;
    return 1;
  }

  // The filter panel: the float torus nearest to a million triangles, one thread.
  double triangles = 0;
  for (const auto& row : filter)
  {
    const double t = Number(row, "triangles");
    if (triangles == 0 || std::abs(std::log(t / 1e6)) < std::abs(std::log(triangles / 1e6)))
    {
      triangles = t;
    }
  }
  std::vector<int> resolutions;
  for (const auto& row : accuracy)
  {
    if (row.at("surface") == surface)
    {
      resolutions.push_back(static_cast<int>(Number(row, "n")));
    }
  }
  std::sort(resolutions.begin(), resolutions.end());
  resolutions.erase(std::unique(resolutions.begin(), resolutions.end()), resolutions.end());
  if (resolution == 0 && !resolutions.empty())
  {
    resolution = resolutions[resolutions.size() / 2];
  }
  std::vector<Point> filterPoints;
  double floor = 0.0;
  for (const auto& row : filter)
  {
    if (row.at("precision") != "float" || Number(row, "threads") != 1 ||
      Number(row, "triangles") != triangles)
    {
      continue;
    }
    const std::string name = row.at("filter");
    if (name == "floor")
    {
      floor = Number(row, "mtri_per_s");
      continue;
    }
    for (const auto& a : accuracy)
    {
      if (a.at("filter") == name && a.at("surface") == surface && Number(a, "n") == resolution)
      {
        filterPoints.push_back({ name,
          Number(row, "mtri_per_s"),
          Number(a, "mean"),
          name != "vtkPolyDataTangents",
          "" });
      }
    }
  }
  std::vector<Point> renderPoints;
  for (const auto& row : rendering)
  {
    std::string label = row.at("configuration");
    label = (label.rfind("VTK mapper, ", 0) == 0 ? "VTK: " + label.substr(12) : label) + ", " +
      row.at("lighting");
    renderPoints.push_back({ label,
      Number(row, "ms_per_frame"),
      Number(row, "geometry_mean_error"),
      row.at("configuration").rfind("ours", 0) == 0,
      row.at("lighting") });
  }

  std::ostringstream filterTitle, xTitle, yTitle;
  filterTitle << "Tangent filters: speed vs accuracy";
  xTitle << "M triangles/s (" << Bench::Count(static_cast<long long>(triangles))
         << " triangles, float, 1 thread), higher is better";
  yTitle << "mean angle to dP/du, degrees (" << surface << ", n = " << resolution
         << "), lower is better";
  auto left = Panel(filterTitle.str(),
    filterPoints,
    true,
    xTitle.str(),
    yTitle.str(),
    floor,
    "floor: read inputs, write outputs");
  auto right = Panel("Normal-mapped rendering (llvmpipe): time vs error",
    renderPoints,
    false,
    "ms per frame, lower is better",
    "mean channel error vs displaced geometry (levels), lower is better",
    0.0,
    "");

  vtkNew<vtkImageAppend> append;
  append->SetAppendAxis(0);
  std::vector<vtkSmartPointer<vtkWindowToImageFilter>> grabs;
  for (vtkRenderWindow* window : { left.Get(), right.Get() })
  {
    auto grab = vtkSmartPointer<vtkWindowToImageFilter>::New();
    grab->SetInput(window);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->Update();
    append->AddInputConnection(grab->GetOutputPort());
    grabs.push_back(grab);
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName((out + "/benchmarks.png").c_str());
  writer->SetInputConnection(append->GetOutputPort());
  writer->Write();
  std::cout << "wrote " << out << "/benchmarks.png (" << filterPoints.size() << " filters, "
            << renderPoints.size() << " rendering configurations)" << std::endl;
  return filterPoints.empty() || renderPoints.empty() ? 1 : 0;
}
