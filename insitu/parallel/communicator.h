// insitu/parallel/communicator.h - the MPI communicator the solver handed over, with the few
// collectives the runtime uses, each named for what it is for. Every rank must call the same
// collectives in the same order; the runtime only calls them at fixed points of a step, after
// turning local failures into flags (agree()), so that no rank waits for one that threw.
// Counts the bytes this rank sends, for the stats. The only place that includes <mpi.h>.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace voxspan {

// A failure somewhere: the lowest rank that failed and its message; ok when none did.
struct Agreement {
  bool ok = true;
  int rank = -1;
  std::string message;
};

class Communicator {
 public:
  // `fortran_handle`: MPI_Comm_c2f of the solver's communicator. MPI must be initialized.
  explicit Communicator(int fortran_handle);
  ~Communicator();
  Communicator(const Communicator&) = delete;
  Communicator& operator=(const Communicator&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  // This rank's place among the ranks of its node (shared memory), and their number.
  int node_rank() const { return node_rank_; }
  int node_size() const { return node_size_; }

  // Every rank says whether its part went well; all learn the lowest failing rank's message.
  Agreement agree(bool ok, const std::string& message);
  // agree(), then on every rank voxspan::Error "rank <r>: <its message>" when any failed (the
  // message alone with one rank): the ranks fail together, each naming the one that failed first.
  void agree_or_throw(bool ok, const std::string& message);
  // Element-wise over all ranks, in place.
  void min(std::span<double> values);
  void max(std::span<double> values);
  void sum(std::span<std::int64_t> values);
  void sum(std::span<double> values);
  // Rank `root`'s text on every rank.
  std::string broadcast(const std::string& text, int root = 0);
  // Rank `root`'s bytes over every rank's, in place (every rank gives as many).
  void broadcast(std::span<std::byte> bytes, int root = 0);
  // Every rank's bytes, on the root only (in rank order; empty elsewhere).
  std::vector<std::vector<std::byte>> gather(std::span<const std::byte> bytes, int root = 0);
  // Rank r sends send[d] to rank d and receives what every rank sent it, in rank order. The
  // sizes go first (an all-to-all of counts), so a rank with nothing to send sends no data.
  std::vector<std::vector<std::byte>> exchange(const std::vector<std::vector<std::byte>>& send);

  // Bytes this rank has sent (data and counts) since construction: a stage counts its own as
  // the difference across it, so that no reader resets what another one counts.
  std::int64_t bytes_sent() const { return bytes_sent_; }

 private:
  struct Handles;  // the MPI_Comm objects, in communicator.cpp (no header needs <mpi.h>)
  std::unique_ptr<Handles> mpi_;
  int rank_ = 0, size_ = 1, node_rank_ = 0, node_size_ = 1;
  std::int64_t bytes_sent_ = 0;
};

}  // namespace voxspan
