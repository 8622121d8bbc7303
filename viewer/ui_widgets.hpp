// Small Dear ImGui helpers the viewer's window and panels share: the shortcut list (the help overlay), sizes
// of buttons and checkboxes, rows that wrap in a narrow panel, radio rows and tables.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>

namespace cudahull::viewer {

struct Shortcut {
  const char* keys;
  const char* what;
};
constexpr Shortcut kShortcuts[] = {
    {"S, Right", "one step (one iteration of Algorithm 1)"},
    {"Left", "back one step (replays from the start)"},
    {"Space", "run / pause"},
    {"E", "run to the end"},
    {"R", "reset to position 0 (the bare points)"},
    {"1 .. 5", "toggle hull, wireframe, internal, external, vertices"},
    {"C", "points coloured by state / by associated face"},
    {"A", "faces coloured by last step's state / by age"},
    {"F", "fit the view to the data"},
    {"Home", "reset the view"},
    {"Ctrl-C", "copy the view as JSON"},
    {"Ctrl-V", "paste a view (JSON)"},
    {"Left drag", "orbit"},
    {"Right / middle drag, Shift + left drag", "pan"},
    {"Wheel", "zoom"},
    {"Hover", "a point's or face's ids, state, face and signed distance"},
    {"Click", "on a point: its route through the step (Explain point); on a face: its cell (Fig. 2)"},
    {"N", "toggle the edge normals of all faces"},
    {"W", "toggle the last step's swaps (with their sequence numbers) and removals"},
    {"G", "toggle the last step's refinements (parent faces, apexes)"},
    {"J", "jump to the next step with a rejected swap"},
    {"D", "show / hide the debugger panel"},
    {"F1, ?", "this help"},
    {"Ctrl-Q", "quit"},
};

// "12.3 MiB", "4.0 KiB" or "17 B".
std::string format_bytes(std::uint64_t b);
// The width a button or a checkbox with `label` takes in the current style.
float button_width(const char* label);
float checkbox_width(const char* label);
// Puts the next item (`width` wide) beside the last one when it fits, else on a new line: rows of buttons
// and checkboxes wrap in a narrow panel instead of running past its edge.
void same_line_if_fits(float width);
// "label:" and a radio button a choice on one line; returns the index of the chosen one (`value` if none
// is clicked).
int radio_row(const char* label, int value, std::initializer_list<const char*> choices);
// BeginTable with one header a column, as wide as their contents; EndTable when it returns true.
bool begin_table_with_headers(const char* id, std::initializer_list<const char*> columns);

}  // namespace cudahull::viewer
