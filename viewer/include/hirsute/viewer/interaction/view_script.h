// The viewer's scripted mode (`hirsute view --commands "…"` or `--script FILE`): the actions of
// the mouse and the keys as text, run in order without a person, for tests and for users who
// want the same pictures again. Commands are separated by `;` or new lines; `#` starts a comment.
//
//   rotate H V       turn the plant H degrees about the vertical, V about the horizontal axis
//   roll D           roll it D degrees clockwise
//   zoom F           magnify by F
//   pan X Y          move it right by X and up by Y window heights
//   reset            back to the view file's camera
//   step [N]         N derivation steps forward (default 1; negative goes back)
//   back [N]         N steps back
//   goto N           show derivation step N
//   animate          play the animation (the .a file's frames) to its end
//   wireframe on|off polygons as their edges
//   help on|off      the key map overlay;  panel on|off  the constants panel
//   define NAME VAL  set a #define constant and re-derive;  save  write the constants to the .l
//   color I R G B    colour I of the colour map (0..1 each); material I FIELD V…  a material's
//                    ambient|diffuse|specular|emission R G B, shininess S or transparency T
//   panel slider|button|range NAME …  a control of the model's .pnl panels, or a slider's range
//   undo [E], redo [E]  the last edit of the editor E (colors, panel; default the last edited)
//   save colors|panel  write the editor's file;  create colors|materials|panel  make one
//   colors on|off, controls on|off  the palette editor and the .pnl panels
//   wait-reload [S]  wait (up to S seconds, default 10) until a model file changes and is re-read
//   sleep S          wait S seconds, drawing
//   NAME on|off      show or hide the organ NAME (live_organ.h: hairs, feathers …), as its key
//   …                each organ's own commands (its LiveOrganType's actions; docs/viewer.md)
//   measure [N]      print the frame time over N frames still and N frames moving
//   screenshot FILE [ui|shown]  write the window's picture to a PNG (with ui: with the overlays;
//                    shown: what the window shows now, not drawn again)
//   function NAME point I X Y | add X Y | remove I | undo | redo | save | open | close
//   contour NAME point I X Y [Z] | add I X Y [Z] | remove I | undo | redo | save | open | close
//   surface NAME point I X Y Z | undo | redo | save | open | close
//                    the shape editors' actions (shape_workbench.h), each written at once
//   quit             close the window
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

struct ViewCommand {
  enum class Kind {
    Rotate,
    Roll,
    Zoom,
    Pan,
    Reset,
    Step,
    Back,
    Goto,
    Animate,
    Organ,  // an organ's: `NAME on|off` (action -1) or one of its actions (live_organ.h)
    Wireframe,
    Help,
    Panel,
    Define,
    Save,
    WaitReload,
    Sleep,
    Measure,
    Screenshot,
    Quit,
    // The editors (docs/viewer.md, "Editors")
    Color,
    Material,
    Undo,
    Redo,
    Create,
    Colors,
    Controls,
    Shape  // `function`, `contour` or `surface`: words are the editor, NAME and the action
  };
  Kind kind;
  std::vector<double> numbers;
  std::vector<std::string> words;  // file names, define names and values, on/off
  SourceLocation where;
  // Kind::Organ: the organ's place in liveOrgans() and its action (-1: show or hide it).
  std::size_t organ = 0;
  int action = -1;
};

// Parses a script; `fileName` names it in messages ("--commands" for the command line's text).
// Throws DiagnosticError ("file:line:col: error: …") for an unknown command or wrong arguments.
std::vector<ViewCommand> parseViewScript(const std::string& text, const std::string& fileName);

}  // namespace hirsute
