// A request body read while its answer is written: the points of a streamed projection sent in
// binary. A reader thread takes the body from the connection (BodySource::read) into a buffer of
// whole records that the answering thread takes a window at a time, so that the memory held is a
// few windows whatever the body's length.
//
// Flow control. A client that reads the answer while it sends (full duplex) is held back once
// `ahead_bytes` of the body wait unread: TCP's window then slows its sending. A client that sends
// the whole body before it reads anything (most HTTP clients) would deadlock against that rule
// once the answer fills the socket buffers - the server blocked writing, the client blocked
// sending - so once a write of the answer has waited kStall for the client, the reader reads on
// without bound until the write goes on: such a client costs the body's size in memory (at most
// --max-body-bytes), as a JSON batch does, and kStall of time. The answer is written in pieces of
// at most kWritePiece bytes, so that a client reading slowly but steadily (kWritePiece per kStall)
// is not taken for one that does not read.
//
// Before the answer starts (the status line is not sent yet) the reader stops at `first_bytes`
// (or the body's end): the handler checks those points and can still answer an error. The reader
// then waits for open(), so that it never runs while the HTTP layer writes the response head.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace footpoint::server {

// A request body not yet read (the HTTP layer's reader, with its length).
struct BodySource {
  std::size_t length = 0;  // Content-Length
  using Receiver = std::function<bool(const char* data, std::size_t size)>;
  // Calls the receiver with the body's successive pieces to its end; false when the body ended
  // short (the client closed, or sent nothing for the read timeout) or the receiver returned
  // false. Called once, from one thread at a time.
  std::function<bool(const Receiver&)> read;
};

class StreamedBody {
 public:
  enum class End { reading, whole, short_body, stopped };
  static constexpr std::chrono::milliseconds kStall{100};
  static constexpr std::size_t kWritePiece = 64 << 10;

  // Starts reading `source`, whose length is a whole number of `record_bytes` records.
  StreamedBody(BodySource source, std::size_t record_bytes, std::size_t first_bytes, std::size_t ahead_bytes);
  ~StreamedBody();  // stops the reader and waits for it
  StreamedBody(const StreamedBody&) = delete;
  StreamedBody& operator=(const StreamedBody&) = delete;

  // Waits until the first bytes are held or the body ended; returns the records held then, copied
  // into `out` (they stay to be taken).
  std::size_t wait_first(std::string& out);
  // Lets the reader go on past the first bytes (the answer's head is sent).
  void open();
  // Moves up to `max_records` whole records into `out` (replacing its content), waiting for them
  // (or for the body's end); returns the records moved, 0 at the end of what was read.
  std::size_t take(std::size_t max_records, std::string& out);
  // The answering thread starts (true) or ends (false) a write of the answer (kWritePiece bytes
  // at most).
  void writing(bool inside);
  // Reads the rest of the body and drops it; true when the body was whole.
  bool drain();
  // Stops the reader (the receiver refuses the next piece) and waits for it.
  void stop();
  End end() const;
  std::size_t bytes_read() const;

 private:
  bool receive(const char* data, std::size_t size);
  // Appends the first `bytes` held bytes to out, and drops them when `drop` (take).
  void copy_front(std::size_t bytes, std::string& out, bool drop);

  BodySource source_;
  const std::size_t record_bytes_, first_bytes_, ahead_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  // The bytes read and not taken: blocks of kBlock bytes (the last one filling), the first one's
  // from front_at_ on, held_ in all. Blocks, not one growing buffer: a body held whole for a
  // client that does not read costs its size, not the two or three times of a doubling copy.
  static constexpr std::size_t kBlock = 1 << 20;
  std::deque<std::string> blocks_;
  std::size_t front_at_ = 0, held_ = 0;
  std::size_t read_ = 0;  // body bytes read so far
  bool open_ = false, writing_ = false, stopping_ = false, dropping_ = false;
  std::chrono::steady_clock::time_point write_start_;
  End end_ = End::reading;
  std::thread reader_;
};

}  // namespace footpoint::server
