// check_render RENDER_EXE OUT.png ARGS...: runs `RENDER_EXE ARGS... --size 400 300 OUT.png` (or,
// when one of ARGS is `{png}`, `RENDER_EXE ARGS... --size 400 300` with OUT.png in its place) and
// checks the picture: 400 × 300 pixels, many colours (a colour map, edges and text, not a blank
// or one-colour window), and not only background. Exit code 77 (skipped) when no X display
// can be opened; 0 when the picture passes, 1 otherwise.

#include <sys/wait.h>
#include <unistd.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "render_picture.h"

namespace {

constexpr int kSkip = 77;

/// Runs `argv` and returns its exit code (-1 if it did not exit normally).
int run(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    execv(argv[0], argv.data());
    std::perror("execv");
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: check_render RENDER_EXE OUT.png ARGS...\n");
    return 2;
  }
  if (!render_picture::display_available()) {
    std::printf("check_render: no X display can be opened (run under xvfb-run): skipped\n");
    return kSkip;
  }
  const std::string png = argv[2];
  std::vector<std::string> command = {argv[1]};
  bool placed = false;
  for (int i = 3; i < argc; i++) {
    const bool here = std::string(argv[i]) == "{png}";
    command.push_back(here ? png : argv[i]);
    placed = placed || here;
  }
  for (const char* a : {"--size", "400", "300"}) command.push_back(a);
  if (!placed) command.push_back(png);
  std::remove(png.c_str());
  const int code = run(command);
  if (code == kSkip) return kSkip;
  if (code != 0) {
    std::fprintf(stderr, "check_render: the renderer exited with %d\n", code);
    return 1;
  }

  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(png.c_str())) {
    std::fprintf(stderr, "check_render: %s is not a PNG file\n", png.c_str());
    return 1;
  }
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const int components = image->GetNumberOfScalarComponents();
  std::set<unsigned> colours;
  long background = 0;
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  const long count = static_cast<long>(dims[0]) * dims[1];
  for (long p = 0; p < count; p++) {
    const unsigned char* c = pixels + p * components;
    colours.insert((unsigned{c[0]} << 16) | (unsigned{c[1]} << 8) | c[2]);
    if (c[0] == 255 && c[1] == 255 && c[2] == 255) background++;
  }
  const double covered = 1.0 - static_cast<double>(background) / static_cast<double>(count);
  std::printf("check_render: %s: %d x %d, %d components, %zu colours, %.0f%% not background\n", png.c_str(), dims[0],
              dims[1], components, colours.size(), 100 * covered);
  const bool ok = dims[0] == 400 && dims[1] == 300 && components >= 3 && colours.size() >= 50 && covered > 0.03;
  if (!ok) std::fprintf(stderr, "check_render: expected 400 x 300 RGB, >= 50 colours, > 3%% not background\n");
  return ok ? 0 : 1;
}
