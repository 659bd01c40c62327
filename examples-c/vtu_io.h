// vtu_io.h: reading .vtu files with VTK, its error texts turned into exceptions. Shared by the
// C++ examples.

#ifndef IGAPARAM_VTU_IO_H
#define IGAPARAM_VTU_IO_H

#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <fstream>
#include <iostream>
#include <regex>
#include <stdexcept>
#include <string>

namespace vtu_io {

/// The gist of a VTK error text ("ERROR: In <file>, line <n>\n<Class> (<address>): <message>..."):
/// the message's first line, or nothing for the pipeline's generic "returned failure" report.
inline std::string vtk_error_gist(const std::string& text) {
  static const std::regex pattern(R"(^ERROR: In [^\n]*\n[A-Za-z0-9_]+ \(0x[0-9a-fA-F]+\): ([^\n]*))");
  std::smatch match;
  if (!std::regex_search(text, match, pattern)) return text;
  const std::string message = match[1];
  return message.find("returned failure for request") != std::string::npos ? std::string() : message;
}

/// Takes the place of VTK's output window: keeps error texts instead of printing them, so that a
/// failed read or write is reported as one error; warnings go to stderr.
class VtkMessages : public vtkOutputWindow {
 public:
  static VtkMessages* New() { VTK_STANDARD_NEW_BODY(VtkMessages); }
  vtkTypeMacro(VtkMessages, vtkOutputWindow);

  void DisplayErrorText(const char* text) override {
    const std::string gist = vtk_error_gist(text != nullptr ? text : "");
    if (!gist.empty()) errors_ += (errors_.empty() ? "" : "; ") + gist;
    failed_ = true;
  }
  void DisplayWarningText(const char* text) override {
    if (text != nullptr) std::cerr << "VTK warning: " << text;
  }
  void DisplayGenericWarningText(const char* text) override { DisplayWarningText(text); }
  void DisplayText(const char* text) override {
    if (text != nullptr) std::cerr << text;
  }

  /// Puts back the output window this one replaced, then throws if VTK reported an error or if
  /// `failed`: `what` says which operation.
  void throw_if_failed(const std::string& what, bool failed = false) {
    if (previous_ != nullptr) vtkOutputWindow::SetInstance(previous_);
    previous_ = nullptr;
    if (failed_ || failed) throw std::runtime_error(what + (errors_.empty() ? std::string() : ": " + errors_));
  }

 private:
  std::string errors_;
  bool failed_ = false;
  vtkSmartPointer<vtkOutputWindow> previous_;

  friend vtkSmartPointer<VtkMessages> capture_vtk_messages();
};

/// Installs a fresh VtkMessages as VTK's output window and returns it.
inline vtkSmartPointer<VtkMessages> capture_vtk_messages() {
  auto messages = vtkSmartPointer<VtkMessages>::New();
  messages->previous_ = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(messages);
  return messages;
}

/// Reads the .vtu file `path`; throws with VTK's message when it cannot, or when it holds no cells.
inline vtkSmartPointer<vtkUnstructuredGrid> read_grid(const std::string& path) {
  if (!std::ifstream(path).good()) throw std::runtime_error("cannot open " + path);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  auto messages = capture_vtk_messages();
  reader->SetFileName(path.c_str());
  reader->Update();
  messages->throw_if_failed("cannot read " + path);
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  if (grid == nullptr || grid->GetNumberOfCells() == 0 || grid->GetNumberOfPoints() == 0) {
    throw std::runtime_error(path + " holds no cells");
  }
  return grid;
}


}  // namespace vtu_io

#endif  // IGAPARAM_VTU_IO_H
