// A request body read while its answer is written: the points of a streamed projection sent in
// binary. A reader thread takes the body from the connection (BodySource::read) into a buffer of
// whole records that the answering thread takes a window at a time, so that the memory held is a
// few windows whatever the body's length.
//
// Flow control. A client that reads the answer while it sends (full duplex) is held back once
// `ahead_bytes` of the body wait unread: TCP's window then slows its sending. A client that sends
// the whole body before it reads anything (most HTTP clients) would deadlock against that rule
// once the answer fills the socket buffers - the server blocked writing, the client blocked
// sending - so while the answering thread is inside a write the reader reads on without bound:
// such a client costs the body's size in memory (at most --max-body-bytes), as a JSON batch does.
//
// Before the answer starts (the status line is not sent yet) the reader stops at `first_bytes`
// (or the body's end): the handler checks those points and can still answer an error. The reader
// then waits for open(), so that it never runs while the HTTP layer writes the response head.
#pragma once
#include <condition_variable>
#include <cstddef>
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

  // Starts reading `source`, whose length is a whole number of `record_bytes` records.
  StreamedBody(BodySource source, std::size_t record_bytes, std::size_t first_bytes, std::size_t ahead_bytes);
  ~StreamedBody();  // stops the reader and waits for it
  StreamedBody(const StreamedBody&) = delete;
  StreamedBody& operator=(const StreamedBody&) = delete;

  // Waits until the first bytes are held or the body ended; returns the records held then.
  std::size_t wait_first();
  // The records held now from the first one not taken (valid until the next take or open).
  std::string_view held() const { return std::string_view(held_).substr(taken_); }
  // Lets the reader go on past the first bytes (the answer's head is sent).
  void open();
  // Moves up to `max_records` whole records into `out` (replacing its content), waiting for them
  // (or for the body's end); returns the records moved, 0 at the end of what was read.
  std::size_t take(std::size_t max_records, std::string& out);
  // The answering thread is (not) inside a write of the answer.
  void writing(bool inside);
  // Reads the rest of the body and drops it; true when the body was whole.
  bool drain();
  // Stops the reader (the receiver refuses the next piece) and waits for it.
  void stop();
  End end() const;
  std::size_t bytes_read() const;

 private:
  bool receive(const char* data, std::size_t size);

  BodySource source_;
  const std::size_t record_bytes_, first_bytes_, ahead_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::string held_;  // bytes read and not taken start at taken_
  std::size_t taken_ = 0;
  std::size_t read_ = 0;  // body bytes read so far
  bool open_ = false, writing_ = false, stopping_ = false, dropping_ = false;
  End end_ = End::reading;
  std::thread reader_;
};

}  // namespace footpoint::server
