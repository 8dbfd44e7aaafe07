// The live page's camera controls in an MPI job (run under mpiexec on 2 ranks): the request
// reaches rank 0's server only, yet every rank renders with the camera it gives. An orbit is
// posted between two steps; each rank must log the same camera (rank 0 at the warning level,
// the others at the debug level), and the composited picture must be one process's with the
// same orbit (1e-5 per linear channel) and not the picture before it. Only rank 0 prints.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <mpi.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/image_difference.h"
#include "tests/support/log_capture.h"
#include "tests/support/mpi_tests.h"
#include "voxspan/mpi.h"

namespace voxspan {
namespace {

using test::world_rank;
using test::world_size;

constexpr double kSpacing = 0.05;
constexpr int kSide = 10;
const std::string kToken = "mpi-live-camera-test-token";

// A block of kSide^3 particles with a field varying in space; slabs along x by rank.
struct Share {
  std::vector<double> x, y, z, p;
  Share(int rank, int ranks) {
    for (int k = 0; k < kSide; ++k)
      for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
          if (i * ranks / kSide != rank) continue;
          x.push_back(i * kSpacing), y.push_back(j * kSpacing), z.push_back(k * kSpacing);
          p.push_back(10.0 * i * kSpacing + j * j * kSpacing);
        }
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_scalar("p", p.data());
  }
};

// A port no one listens on now (rank 0 picks it; the job's ranks need the same config).
int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t size = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &size);
  close(fd);
  return ntohs(a.sin_port);
}

// The status of one POST /camera to 127.0.0.1:port (0: no answer).
int post_camera(int port, const std::string& body) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(std::uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    close(fd);
    return 0;
  }
  const std::string request = "POST /camera HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
                              kToken +
                              "\r\nContent-Type: application/x-www-form-urlencoded\r\n"
                              "Content-Length: " +
                              std::to_string(body.size()) + "\r\n\r\n" + body;
  send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string reply;
  char buffer[512];
  for (ssize_t n; (n = recv(fd, buffer, sizeof buffer, 0)) > 0;) reply.append(buffer, size_t(n));
  close(fd);
  return reply.starts_with("HTTP/1.1 ") ? std::stoi(reply.substr(9, 3)) : 0;
}

std::string config(const std::string& name, int port) {
  return "output_folder: " +
         (std::filesystem::temp_directory_path() / ("voxspan-mpi-live-" + name)).string() +
         "\noutputs: {png: {enabled: false}, stats: {enabled: false}}\n"
         "trigger: {every_steps: 1}\nwriter: {fsync: false}\n"
         "views:\n  - {name: v, kind: volume, width: 72, height: 54, quantity: p, legend: false, "
         "caption: '', camera: {direction: [0.3, -1, -0.6], up: [0, 0, 1]}}\n"
         "live: {enabled: true, interactive: true, port: " +
         std::to_string(port) + ", token: " + kToken + "}\n";
}

AdapterOptions options() {
  AdapterOptions o;
  o.classify.particle_spacing = kSpacing;
  return o;
}

std::vector<float> picture(const Adapter& a) {
  const ViewResult& r = dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
  return r.picture ? r.picture->rgba : std::vector<float>{};
}

// This rank's log lines of applied camera changes.
std::vector<std::string> turned(const test::LogCapture& log) {
  std::vector<std::string> lines;
  for (LogLevel level : {LogLevel::warning, LogLevel::debug})
    for (const std::string& m : log.at(level))
      if (m.find("camera turned from the live page") != std::string::npos) lines.push_back(m);
  return lines;
}

TEST(MpiLive, EveryRankRendersWithTheCameraRankZeroReceived) {
  const test::LogCapture log;
  const std::string orbit = "view=v&action=orbit&d_phi=50&d_theta=20";
  int port = world_rank() == 0 ? free_port() : 0;
  MPI_Bcast(&port, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const Share mine(world_rank(), world_size());
  Adapter job = adapter_from_config_text(config("job", port), options(), MPI_COMM_WORLD);
  ASSERT_TRUE(job.execute(1, 0.1, mine.view()).ok());
  const std::vector<float> before = picture(job);
  if (world_rank() == 0) {
    EXPECT_EQ(post_camera(port, orbit), 202);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  ASSERT_TRUE(job.execute(2, 0.2, mine.view()).ok());
  const std::vector<float> after = picture(job);
  job.finish();

  // Rank 0's line on every rank, against the rank's own.
  std::vector<std::string> lines = turned(log);
  ASSERT_EQ(lines.size(), 1u) << "rank " << world_rank() << ":\n" << log.all();
  std::string root_line = lines[0];
  int length = int(root_line.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  root_line.resize(std::size_t(length));
  MPI_Bcast(root_line.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  EXPECT_EQ(lines[0], root_line) << "rank " << world_rank();
  if (world_rank() != 0) return;
  std::printf("every rank: %s\n", root_line.c_str());

  // One process, the same orbit between the same steps.
  const Share all(0, 1);
  const int one_port = free_port();
  Adapter one = adapter_from_config_text(config("one", one_port), options());
  ASSERT_TRUE(one.execute(1, 0.1, all.view()).ok());
  EXPECT_EQ(post_camera(one_port, orbit), 202);
  ASSERT_TRUE(one.execute(2, 0.2, all.view()).ok());
  const double d = test::largest_difference(after, picture(one));
  std::printf(
      "after the orbit, %d ranks against one process: largest difference %.1e; "
      "against the picture before it: %.2f\n",
      world_size(), d, test::largest_difference(after, before));
  EXPECT_LT(d, 1e-5);
  EXPECT_GT(test::largest_difference(after, before), 0.05);
  one.finish();
}

}  // namespace
}  // namespace voxspan

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
