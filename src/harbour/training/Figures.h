#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace harbour::training {

/// How people read one stored figure of an attempt: its words, the unit it is shown in and how its stored
/// (SI) value converts to it, its significant digits, and whether more is better. One table for the
/// console, the reports and the exported records.
struct FigureWords {
  std::string name;    ///< as stored; "*_harsh_moves": every axis's (the label's "{axis}" is the axis)
  std::string label;   ///< "hoist energy", "{axis} harsh moves"
  std::string unit;    ///< as shown: "MJ", "m/s", "" for a count
  double scale = 1.0;  ///< shown = stored × scale
  int digits = 3;      ///< significant digits shown (nothing below a thousandth of the unit)
  bool higher_better = false;
  std::string about;  ///< one sentence: what it measures
};

/// Every figure an attempt stores (sim::Metrics::rows(), the score and the skills), in the order people read
/// them: the score and skills, the task, safety, precision, the machine's and the team's.
const std::vector<FigureWords>& figure_table();

/// The words of a stored figure: its table row (a per-axis row with the axis filled in), or, for a name the
/// table does not know, words made from the name with its unit read from the suffix (name_unit).
FigureWords figure_words(const std::string& name);

/// Where a figure comes in figure_table()'s order (a name it does not know: after every known one).
std::size_t figure_order(const std::string& name);

/// An attempt's or a station's event in words, with its value and text where it carries them: "hard landing
/// at 0.41 m/s", "control device lost", "instructor: hoist brake fault", "move 2 done", "attempt ended by the
/// instructor, score 80".
std::string event_text(const std::string& kind, double value, const std::string& text = "");

/// A value as people read it: "6.60 MJ", "13.6 s", "3", "1.23 m/s".
std::string figure_text(const FigureWords& words, double stored);
std::string figure_text(const std::string& name, double stored);

}  // namespace harbour::training
