// Bad input at the integration level, through the shared library: what a user gets wrong at
// start-up is one clear error before step 1; what goes wrong mid-run (a full disk, a writer
// that cannot keep up) never stops the solver, is reported once, and leaves no partial file
// under a final name. The runs that fill a disk happen in a fresh child process (a private
// tmpfs, or a file-size limit; fresh_child.h), which makes its own GL context.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cfenv>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

#include "dambreak_run.h"
#include "fresh_child.h"
#include "output_files.h"
#include "tests/support/child_process.h"
#include "tests/support/error_message.h"
#include "tests/support/log_capture.h"
#include "tests/support/temp_folder.h"
#include "voxspan/adapter.h"
#include "voxspan/insitu.h"
#include "voxspan/voxspan.h"

namespace voxspan {
namespace {

std::string start_error(const std::string& yaml) {
  dambreak::DamBreak sim(test::small_dambreak());
  return test::error_message([&] {
    Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml");
  });
}

TEST(StartUp, UnknownConfigKeyIsNamedWithItsLine) {
  const std::string e =
      start_error("output_folder: out\nviews:\n  - name: front\n    shadng: opaque\n");
  EXPECT_NE(e.find("run.yaml:4:5: views[0].shadng: unknown key (did you mean 'shading'?)"),
            std::string::npos)
      << e;
}

TEST(StartUp, UnknownConfigKeyThroughTheCApi) {
  test::TempFolder dir;
  const std::filesystem::path file = dir / "insitu.yaml";
  std::ofstream(file) << "trigger: {every_steps: 10}\nwriter:\n  queue_sise: 4\n";
  voxspan_adapter_options o;
  voxspan_adapter_options_init(&o);
  o.particle_spacing = 0.01;
  voxspan_adapter* a = voxspan_adapter_create_from_config(&o, file.c_str());
  EXPECT_EQ(a, nullptr);
  const std::string e = voxspan_last_error();
  EXPECT_NE(e.find(file.string() + ":3:3: writer.queue_sise: unknown key (did you mean "
                                   "'queue_size'?)"),
            std::string::npos)
      << e;
  voxspan_adapter_destroy(a);
}

TEST(StartUp, OutputFolderThatCannotBeWrittenFailsBeforeStepOne) {
  test::TempFolder dir;
  std::ofstream(dir / "a-file") << "x";
  // A folder under a regular file, and a folder in /proc: neither can exist (root included).
  std::string e = start_error("output_folder: " + (dir / "a-file").string() + "/run\n");
  EXPECT_NE(e.find("cannot use output_folder " + (dir / "a-file").string() + "/run: Not a "),
            std::string::npos)
      << e;
  e = start_error(
      "outputs:\n  vdb: {enabled: true, folder: /proc/voxspan-snapshots}\n"
      "output_folder: " +
      (dir / "ok").string() + "\n");
  EXPECT_NE(e.find("cannot use outputs.vdb folder /proc/voxspan-snapshots"), std::string::npos)
      << e;
}

// The platform the config asks for, where it cannot work (no NVIDIA EGL device here), is one
// error at start-up naming it: no step runs on a renderer that is not there.
TEST(StartUp, AnOutputOfViewsWithNoViewsIsRefused) {
  test::TempFolder dir;
  const std::string e = start_error("output_folder: " + dir.path().string() +
                                    "\nviews: []\noutputs: {cinema: {enabled: true}}\n");
  EXPECT_NE(e.find("outputs.cinema is enabled but the config has no views"), std::string::npos)
      << e;
  // PNG frames are on by default: a run of snapshots alone leaves them with nothing to draw.
  EXPECT_EQ(start_error("output_folder: " + dir.path().string() +
                        "\nviews: []\noutputs: {vdb: {enabled: true}}\n"),
            "");
}

TEST(StartUp, UnusableGlPlatformFailsBeforeStepOne) {
  test::TempFolder dir;
  const char* forced = std::getenv("VOXSPAN_GL_PLATFORM");  // it would override the config
  const std::string saved = forced ? forced : "";
  ::unsetenv("VOXSPAN_GL_PLATFORM");
  const std::string e =
      start_error("output_folder: " + dir.path().string() + "\nrenderer: {gl_platform: nvidia}\n");
  if (!saved.empty()) ::setenv("VOXSPAN_GL_PLATFORM", saved.c_str(), 1);
  if (e.empty()) GTEST_SKIP() << "this machine has an NVIDIA EGL device";
  EXPECT_NE(e.find("cannot create an OpenGL context (platform nvidia"), std::string::npos) << e;
}

// A view too large for the host's memory is refused at start-up with its estimate (it used to
// pass and die of std::bad_alloc 34 s later); the limit is a key.
TEST(StartUp, ViewsLargerThanTheHostMemoryAreRefusedBeforeStepOne) {
  test::TempFolder dir;
  const std::string views = "output_folder: " + dir.path().string() +
                            "\nviews: [{name: huge, width: 16384, height: 16384}]\n";
  std::string e = start_error(views + "renderer: {host_memory_mib: 8192}\n");
  EXPECT_NE(e.find("the views need about 24576 MiB of host memory (huge 16384x16384 24576 MiB"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("over the 8192 MiB they may take (renderer.host_memory_mib)"), std::string::npos)
      << e;
  e = start_error(views + "renderer: {host_memory_mib: 30000}\n");
  EXPECT_EQ(e.find("host memory"), std::string::npos) << e;
}

// A run that ends before writing anything (a solver, or a Python call, that raised first)
// leaves no empty stats file or folders behind; one that wrote keeps them.
TEST(StartUp, ARunThatWroteNothingLeavesNothing) {
  test::TempFolder dir;
  const std::filesystem::path out = dir / "run" / "out";
  const std::string yaml = "output_folder: " + out.string() + "\n";
  dambreak::DamBreak sim(test::small_dambreak());
  { Adapter unused = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml"); }
  EXPECT_FALSE(std::filesystem::exists(dir / "run")) << "left behind: " << out;
  {
    Adapter used = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml");
    EXPECT_EQ(test::run_dambreak(sim, used, 1).failed, 0);
  }
  EXPECT_TRUE(std::filesystem::exists(out / "stats.jsonl"));
  EXPECT_FALSE(test::files_in(out / "frames").empty());
}

// Two runs never share an output folder (their stats lines would splice): the second is refused
// at start-up, naming the folder and the run that holds it. A run into a folder that an earlier
// run wrote says so, once; the lock goes with its run.
TEST(StartUp, ARunsOutputFolderIsItsOwn) {
  test::TempFolder dir;
  const std::filesystem::path out = dir / "out";
  const std::string yaml = "output_folder: " + out.string() + "\n";
  dambreak::DamBreak sim(test::small_dambreak());
  test::LogCapture log;
  {
    Adapter first = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml");
    const std::string e = test::error_message([&] {
      Adapter second = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml");
    });
    EXPECT_NE(e.find("output folder " + out.string() + " is in use by another run (process " +
                     std::to_string(::getpid()) + " on "),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("give each run its own output_folder"), std::string::npos) << e;
    EXPECT_EQ(test::run_dambreak(sim, first, 1).failed, 0);
  }
  EXPECT_FALSE(std::filesystem::exists(out / ".voxspan.lock"));
  EXPECT_EQ(log.at(LogLevel::warning).size(), 0u) << log.all();
  // Each output's own folder outside output_folder is held too: two runs that name one (their
  // output_folders apart) would replace each other's frames and stats.
  {
    const std::string shared = "outputs: {png: {folder: " + (dir / "frames").string() +
                               "}, stats: {folder: " + (dir / "frames").string() + "}}\n";
    Adapter a = adapter_from_config_text("output_folder: " + (dir / "a").string() + "\n" + shared,
                                         test::solver_options(sim), "a.yaml");
    const std::string e = test::error_message([&] {
      Adapter b = adapter_from_config_text("output_folder: " + (dir / "b").string() + "\n" + shared,
                                           test::solver_options(sim), "b.yaml");
    });
    EXPECT_NE(e.find("output folder " + (dir / "frames").string() + " is in use by another run"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("give each run its own outputs.png.folder"), std::string::npos) << e;
  }
  { Adapter again = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml"); }
  const std::vector<std::string> warnings = log.at(LogLevel::warning);
  ASSERT_EQ(warnings.size(), 1u) << log.all();
  EXPECT_NE(warnings[0].find("output folder " + out.string() + " holds files of an earlier run"),
            std::string::npos)
      << warnings[0];
}

// --- a disk that fills mid-run ----------------------------------------------------------

std::map<std::string, std::string> parse_report(const std::string& text) {
  std::map<std::string, std::string> m;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return m;
}

// In the child: 30 steps with frames every 5 steps, snapshots every 10 (about 650 KiB each at
// this size: the 1 MiB tmpfs takes the first and is full at the second), then what the folder
// holds: files under final names that are incomplete, temporaries, error messages.
std::string run_and_inspect(const std::filesystem::path& folder) {
  test::LogCapture log;
  dambreak::DamBreak sim(test::small_dambreak());
  const std::string yaml = "output_folder: " + folder.string() + R"(
trigger: {every_steps: 5, last: true}
views:
  - {name: a, width: 200, height: 120}
  - {name: b, width: 200, height: 120, camera: {direction: [1, 1, -0.5]}}
outputs:
  vdb: {enabled: true, trigger: {every_steps: 10}, attributes: [velocity, density]}
  vtk: {enabled: true, trigger: {every_steps: 10}}
)";
  std::ostringstream r;
  {
    Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "disk.yaml");
    const test::RunResult run = test::run_dambreak(sim, adapter, 30);
    r << "steps=" << run.steps << "\nfailed=" << run.failed << "\n";
    r << "summary=" << adapter.summary() << "\n";
  }
  std::size_t write_errors = 0;
  for (const std::string& m : log.at(LogLevel::error))
    write_errors += m.find("not written") != std::string::npos;
  r << "write_errors=" << write_errors << "\n";
  const auto errors = log.at(LogLevel::error);
  r << "first_error=" << (errors.empty() ? "" : errors[0]) << "\n";
  r << "temporaries=" << test::temporaries_under(folder).size() << "\n";
  std::size_t finals = 0, broken = 0;
  for (const std::string& name : test::files_in(folder / "frames")) {
    ++finals;
    broken += !test::read_png_file(folder / "frames" / name).ok;
  }
  for (const std::string& name : test::files_in(folder / "snapshots")) {
    ++finals;
    broken += !test::read_vdb(folder / "snapshots" / name).ok;
  }
  for (const std::string& name : test::files_in(folder / "vtk")) {
    ++finals;
    if (name.ends_with(".vtp")) broken += !test::read_vtp(folder / "vtk" / name).ok;
    if (name.ends_with(".vti")) broken += !test::read_vti(folder / "vtk" / name).ok;
  }
  bool complete = false;
  for (const std::string& line : test::read_lines(folder / "stats.jsonl", &complete))
    broken += line.rfind("{\"step\":", 0) != 0 || line.back() != '}';
  broken += !complete;
  r << "finals=" << finals << "\nbroken=" << broken << "\n";
  return r.str();
}

void expect_run_went_on(const std::map<std::string, std::string>& r, const std::string& why) {
  std::printf("%s\n%s\n", r.at("summary").c_str(), r.at("first_error").c_str());
  EXPECT_EQ(r.at("steps"), "30");  // the solver never stopped
  EXPECT_EQ(r.at("failed"), "0");  // writes are the writer's: no step failed for them
  EXPECT_EQ(r.at("write_errors"), "1") << r.at("first_error");  // reported once
  EXPECT_NE(r.at("first_error").find(why), std::string::npos) << r.at("first_error");
  EXPECT_NE(r.at("summary").find("files failed"), std::string::npos) << r.at("summary");
  EXPECT_EQ(r.at("temporaries"), "0");
  EXPECT_EQ(r.at("broken"), "0");           // no partial file under a final name
  EXPECT_GT(std::stoi(r.at("finals")), 0);  // the disk took some files before it filled
}

TEST(MidRun, DiskFillsUp) {
  if (const char* folder = test::child_folder())
    return test::write_child_report(run_and_inspect(folder));
  test::TempFolder dir;
  const std::filesystem::path mount_point = dir / "small";
  std::filesystem::create_directories(mount_point);
  const std::string report =
      test::run_test_in_fresh_process(mount_point, dir / "report.txt", [&]() -> std::string {
        const bool root = ::geteuid() == 0;
        const uid_t uid = ::geteuid();
        const gid_t gid = ::getegid();
        if (::unshare(root ? CLONE_NEWNS : (CLONE_NEWUSER | CLONE_NEWNS)) != 0)
          return "skip=unshare\n";
        if (!root) {
          std::ofstream("/proc/self/setgroups") << "deny";
          std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
          std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
        }
        if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0)
          return "skip=private\n";
        if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=1m") != 0)
          return "skip=mount\n";
        return "";
      });
  const auto r = parse_report(report);
  if (r.count("skip"))
    GTEST_SKIP() << "no tmpfs mount in a namespace here (" << r.at("skip") << ")";
  ASSERT_TRUE(r.count("steps")) << report;
  expect_run_went_on(r, "No space left on device");
}

TEST(MidRun, FileSizeLimitFailsTheLargeFiles) {
  if (const char* folder = test::child_folder())
    return test::write_child_report(run_and_inspect(folder));
  test::TempFolder dir;
  const std::string report =
      test::run_test_in_fresh_process(dir / "run", dir / "report.txt", [&]() -> std::string {
        ::signal(SIGXFSZ, SIG_IGN);  // write(2) returns EFBIG instead of killing the process
        const struct rlimit limit { 48 << 10, 48 << 10 };
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return "skip=setrlimit\n";
        return "";
      });
  const auto r = parse_report(report);
  ASSERT_FALSE(r.count("skip")) << report;
  ASSERT_TRUE(r.count("steps")) << report;
  expect_run_went_on(r, "File too large");
}

// A solver that exits without finish() (a C program returning from main, exit() on an error
// path, Fortran's error stop) still gets the files its last steps queued, and exits cleanly:
// without the adapter's exit handler the writer thread raced exit()'s static destructors
// (crashes in OpenVDB's logging) and the last snapshot was lost.
TEST(MidRun, ExitWithoutFinishWritesTheQueuedFiles) {
  if (const char* folder = test::child_folder()) {
    dambreak::DamBreak sim(test::small_dambreak());
    const std::string yaml = std::string("output_folder: ") + folder + R"(
trigger: {every_steps: 2, last: true}
views: [{name: a, width: 96, height: 64}]
outputs:
  vdb: {enabled: true, trigger: {last: true}, attributes: [velocity]}
)";
    // Never destroyed, as a C solver's adapter is when main returns.
    auto* adapter =
        new Adapter(adapter_from_config_text(yaml, test::solver_options(sim), "x.yaml"));
    for (std::int64_t step = 1; step <= 6; ++step) {
      sim.step();
      const dambreak::Fluid& f = sim.fluid();
      const auto particles = ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                                 .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data());
      if (step < 6) adapter->execute(step, sim.time(), particles);
      else adapter->execute_last(step, sim.time(), particles);
    }
    test::write_child_report("ran=1\n");
    std::exit(0);
  }
  test::TempFolder dir;
  int status = -1;
  const std::string report = test::run_test_in_fresh_process(
      dir / "run", dir / "report.txt",
      [] {
        // The run leaves its adapter to exit() on purpose: under the sanitizers all it holds
        // would read as leaked.
        const char* asan = std::getenv("ASAN_OPTIONS");
        ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":detect_leaks=0").c_str(), 1);
        return std::string();
      },
      &status);
  ASSERT_EQ(report, "ran=1\n");
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "wait status " << status;
  EXPECT_EQ(test::files_in(dir / "run" / "frames").size(), 3u);
  const auto snapshots = test::files_in(dir / "run" / "snapshots");
  ASSERT_EQ(snapshots.size(), 1u);
  EXPECT_TRUE(test::read_vdb(dir / "run" / "snapshots" / snapshots[0]).ok);
  EXPECT_TRUE(test::temporaries_under(dir / "run").empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "run" / ".voxspan.lock"));
}

// A 4 x 4 x 4 block at spacing 0.01, as x, y, z of each particle.
std::vector<float> block_of_64() {
  std::vector<float> xyz;
  for (int i = 0; i < 64; ++i)
    xyz.insert(xyz.end(), {0.01f * float(i % 4), 0.01f * float(i / 4 % 4), 0.01f * float(i / 16)});
  return xyz;
}

// A config with one 64x48 view rendered every step and `outputs` (the map's lines) in `dir`.
std::string one_view_every_step(const test::TempFolder& dir, const std::string& outputs) {
  return "output_folder: " + dir.path().string() +
         "\ntrigger: {every_steps: 1}\nviews: [{name: a, width: 64, height: 48}]\noutputs:" +
         outputs;
}

AdapterOptions spacing_options() {
  AdapterOptions options;
  options.classify.particle_spacing = 0.01;
  return options;
}

// Zero particles and NaN positions are valid steps for every output: pictures of the empty
// environment, snapshots of nothing, the NaNs counted and left out.
TEST(MidRun, EmptyAndNanStepsRenderAndWrite) {
  test::TempFolder dir;
  test::LogCapture log;
  const std::string yaml = one_view_every_step(dir, R"(
  vdb: {enabled: true, trigger: {every_steps: 1}}
  vtk: {enabled: true, trigger: {every_steps: 1}}
)");
  Adapter adapter = adapter_from_config_text(yaml, spacing_options(), "empty.yaml");
  EXPECT_TRUE(adapter.execute(1, 0.0, ParticleView()).ok()) << adapter.last_stats().status.message;
  std::vector<float> xyz = block_of_64();
  xyz[3 * 5] = std::nanf("");
  EXPECT_TRUE(adapter.execute(2, 0.1, ParticleView::aos(xyz.data(), 64)).ok())
      << adapter.last_stats().status.message;
  EXPECT_EQ(adapter.last_stats().counts.dropped_nonfinite, 1u);
  adapter.finish();
  EXPECT_EQ(test::files_in(dir / "frames"),
            (std::vector<std::string>{"a_00000001.png", "a_00000002.png"}));
  EXPECT_TRUE(test::read_png_file(dir / "frames" / "a_00000001.png").ok);
  EXPECT_TRUE(test::read_vdb(dir / "snapshots" / "fluid_00000001.vdb").ok);
  EXPECT_TRUE(test::read_vdb(dir / "snapshots" / "fluid_00000002.vdb").ok);
  EXPECT_TRUE(test::read_vtp(dir / "vtk" / "particles_00000002.vtp").ok);
  EXPECT_EQ(log.at(LogLevel::error).size(), 0u) << log.all();
}

// An attribute the solver does not pass, named by an output (a typo the config check cannot
// see): that output fails on its steps, naming its key, line and the near miss; the pictures, the
// stats and the outputs that name no such attribute are all written.
TEST(MidRun, AnOutputsUnknownAttributeFailsThatOutputAlone) {
  test::TempFolder dir;
  test::LogCapture log;
  const std::string yaml = one_view_every_step(dir, R"(
  stats: {enabled: true}
  vdb: {enabled: true, trigger: {every_steps: 2}, attributes: [velocty]}
  vtk: {enabled: true, trigger: {every_steps: 1}, attributes: [velocity]}
)");
  Adapter adapter = adapter_from_config_text(yaml, spacing_options(), "typo.yaml");
  const std::vector<float> xyz = block_of_64();
  const std::vector<float> velocity(3 * 64, 1.0f);
  const ParticleView particles =
      ParticleView::aos(xyz.data(), 64).with_vector("velocity", velocity.data());
  EXPECT_TRUE(adapter.execute(1, 0.0, particles).ok()) << adapter.last_stats().status.message;
  const Status vdb_step = adapter.execute(2, 0.1, particles);
  EXPECT_FALSE(vdb_step.ok());
  EXPECT_NE(vdb_step.message.find(
                "outputs.vdb: typo.yaml:6:8: outputs.vdb.attributes \"velocty\": the solver "
                "passes no attribute of that name (did you mean \"velocity\"? "
                "it passes: velocity)"),
            std::string::npos)
      << vdb_step.message;
  adapter.finish();
  EXPECT_EQ(test::files_in(dir / "frames"),
            (std::vector<std::string>{"a_00000001.png", "a_00000002.png"}));
  EXPECT_TRUE(test::read_vtp(dir / "vtk" / "particles_00000002.vtp").ok);
  EXPECT_FALSE(std::filesystem::exists(dir / "snapshots" / "fluid_00000002.vdb"));
  std::ifstream stats(dir / "stats.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(stats, line)) ++lines;
  EXPECT_EQ(lines, 2);
}

// A solver built to trap floating-point exceptions (gfortran's -ffpe-trap=invalid,zero,overflow)
// renders on either renderer, and gets its traps back after each call: with no renderer named,
// where EGL's only device is llvmpipe, the automatic choice makes no GL context; with the GL
// renderer named, llvmpipe (whose start-up and shaders raise them) runs with the traps held.
std::string render_with_traps_on(const std::string& renderer) {
  test::TempFolder dir;
  return test::run_in_child([&] {
    const int traps = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;
    std::feclearexcept(FE_ALL_EXCEPT);  // the flags the tests before this one raised
    feenableexcept(traps);
    std::string said;
    {
      Adapter adapter = adapter_from_config_text(
          "output_folder: " + dir.path().string() + "\n" + renderer +
              "views: [{width: 64, height: 48}, {kind: volume, width: 64, height: 48}]\n",
          spacing_options(), "trap.yaml");
      const std::vector<float> xyz = block_of_64();
      const Status s = adapter.execute(0, 0.0, ParticleView::aos(xyz.data(), 64));
      adapter.finish();
      said = s.ok() ? "rendered" : s.message;
    }
    if (fegetexcept() != traps) said += "; the solver's traps were not restored";
    if (std::fetestexcept(FE_ALL_EXCEPT) != 0) said += "; the library's flags were left raised";
    return said;
  });
}

TEST(StartUp, ASolverThatTrapsFloatingPointExceptionsRenders) {
  EXPECT_EQ(render_with_traps_on(""), "rendered");
  EXPECT_EQ(render_with_traps_on("renderer: {backend: cpu}\n"), "rendered");
}

TEST(StartUp, ASolverThatTrapsFloatingPointExceptionsRendersOnLlvmpipe) {
  EXPECT_EQ(render_with_traps_on("renderer: {backend: gl}\n"), "rendered");
}

// A NaN time fails each render step, said; the step triggers still fire on their steps (a NaN
// planned the step twice, and neither plan fired: no frame and no word).
TEST(MidRun, ANanTimeIsSaidOnEveryRenderStep) {
  test::TempFolder dir;
  test::LogCapture log;
  const std::string yaml = "output_folder: " + dir.path().string() +
                           "\ntrigger: {every_steps: 2, first: true}\nviews: [{name: a, width: "
                           "64, height: 48}]\noutputs: {png: {enabled: false}, stats: {enabled: "
                           "false}}\n";
  Adapter adapter = adapter_from_config_text(yaml, spacing_options(), "nan.yaml");
  const std::vector<float> xyz = block_of_64();
  const ParticleView particles = ParticleView::aos(xyz.data(), 64);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::int64_t> failed;
  for (std::int64_t step = 1; step <= 5; ++step) {
    const Status s = adapter.execute(step, nan, particles);
    if (s.ok()) continue;
    failed.push_back(step);
    EXPECT_EQ(s.code, StatusCode::invalid_input);
    EXPECT_NE(s.message.find("the simulated time is nan"), std::string::npos) << s.message;
  }
  EXPECT_EQ(failed, (std::vector<std::int64_t>{1, 2, 4}));
  EXPECT_TRUE(adapter.execute(6, 0.5, particles).ok());
  // Nothing enabled: said so, not an empty list.
  EXPECT_NE(adapter.summary().find("written: nothing (no output is enabled);"), std::string::npos)
      << adapter.summary();
}

// Every view and output that fails a step is named in its status, not the first alone.
TEST(MidRun, EveryFailingViewAndOutputIsNamed) {
  test::TempFolder dir;
  test::LogCapture log;
  const std::string yaml = "output_folder: " + dir.path().string() + R"(
views:
  - {name: good, width: 64, height: 48}
  - {name: speed, width: 64, height: 48, color_by: speed}
  - {name: pressure, kind: slice, width: 64, height: 48, quantity: pressure}
outputs:
  vdb: {enabled: true, attributes: [velocty]}
)";
  Adapter adapter = adapter_from_config_text(yaml, spacing_options(), "views.yaml");
  const std::vector<float> xyz = block_of_64();
  const std::vector<float> velocity(3 * 64, 1.0f);
  const Status s = adapter.execute(
      0, 0.0, ParticleView::aos(xyz.data(), 64).with_vector("velocity", velocity.data()));
  EXPECT_FALSE(s.ok());
  for (const char* named : {"view speed: views.yaml:4:5: views[1].color_by \"speed\"",
                            "; view pressure: views.yaml:5:5: views[2].quantity \"pressure\"",
                            "; outputs.vdb: views.yaml:7:8: outputs.vdb.attributes \"velocty\""})
    EXPECT_NE(s.message.find(named), std::string::npos) << named << "\n" << s.message;
  adapter.finish();
  EXPECT_EQ(test::files_in(dir / "frames"), (std::vector<std::string>{"good_00000000.png"}));
}

// --- a writer queue that overflows ------------------------------------------------------

std::int64_t number_before(const std::string& text, const std::string& what) {
  std::smatch m;
  return std::regex_search(text, m, std::regex("([0-9]+) " + what)) ? std::stoll(m[1]) : -1;
}

TEST(MidRun, WriterQueueOverflowDropsCountsAndWarns) {
  test::TempFolder dir;
  test::LogCapture log;
  dambreak::DamBreak sim(test::small_dambreak());
  // Five files a step (two frames, a snapshot, VTK files, a stats line) into a queue of one,
  // each synced to disk: the writer cannot keep up, and `drop` must not make the solver wait.
  const std::string yaml = "output_folder: " + dir.path().string() + R"(
trigger: {every_steps: 1}
views:
  - {name: a, width: 96, height: 64}
  - {name: b, width: 96, height: 64, shading: opaque}
outputs:
  vdb: {enabled: true, trigger: {every_steps: 1}}
  vtk: {enabled: true, trigger: {every_steps: 1}}
writer: {queue_size: 1, when_full: drop, fsync: true}
)";
  const int steps = 12;
  std::string summary;
  {
    Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "drop.yaml");
    const test::RunResult run = test::run_dambreak(sim, adapter, steps);
    EXPECT_EQ(run.steps, steps);
    EXPECT_EQ(run.failed, 0) << run.first_failure;
    summary = adapter.summary();
  }
  const std::int64_t dropped = number_before(summary, "files dropped");
  ASSERT_GT(dropped, 0) << summary;
  // Every file is either written or counted as dropped: 5 a step.
  const std::int64_t written = number_before(summary, "PNG") + number_before(summary, "VDB") +
                               number_before(summary, "VTK sets") +
                               number_before(summary, "stats lines");
  EXPECT_EQ(written + dropped, 5 * steps) << summary;
  bool warned = false;
  for (const std::string& m : log.at(LogLevel::warning))
    warned = warned || m.find("writer queue full (1 jobs): dropped") != std::string::npos;
  EXPECT_TRUE(warned) << log.all();
  EXPECT_TRUE(test::temporaries_under(dir.path()).empty());
  for (const std::string& name : test::files_in(dir / "frames"))
    EXPECT_TRUE(test::read_png_file(dir / "frames" / name).ok) << name;
}

}  // namespace
}  // namespace voxspan
