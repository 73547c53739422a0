#pragma once
/// When the writes of a produced exchange are answered, and when its image is saved
/// (docs/mqtt-api.md "Results": a write's result is reported once the datagram carrying it was
/// sent and the image carrying it is saved, or saying that it is not).
///
/// The image file has at most one save under way; a save asked for meanwhile follows it, and
/// holds every write staged by then. While saves succeed, a write is produced first and saved
/// right after: its answer waits for the save. Once a save has failed, and until one succeeds
/// (retried every `retry_interval`), each write is saved before it may be produced. A failed
/// save answers the sent writes it carried `saved: false`, and refuses the queued writes it
/// held: they are never produced.
///
/// Pure: knows the writes by their ids (growing in staging order) and the saves by what the
/// caller reports of them; time is passed in. The caller saves the bytes request() returns,
/// reports each save's completion to on_saved(), and answers the writes each call names.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/exchange/produced_image.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class SaveThenAnswer {
public:
    /// While saves fail, how often the image is saved again without a write asking for it.
    static constexpr std::chrono::seconds retry_interval{1};

    /// `saved`: the file holds the image already; else its first save is due (request()).
    explicit SaveThenAnswer(bool saved) : saved_(saved) {}

    /// Asks for a save of `image` with every staged write applied. Returns the bytes to save now
    /// (valid until the next call), or nullopt while a save is under way: another one follows it
    /// (again() says so), holding whatever is staged then.
    std::optional<std::span<const std::byte>> request(const ProducedImage& image);

    /// A write was staged: true when it must be saved before it may be produced (request() a
    /// save): until a save succeeds.
    bool on_staged() const { return !saved_; }

    /// The last staged write a production may apply (ProducedImage::produce's `through`): every
    /// one while saves succeed, else only those the file holds.
    std::uint64_t produce_through() const {
        return saved_ ? ProducedImage::no_limit : saved_through_;
    }

    struct Sent {
        /// The carried writes to answer `ok` now, in staging order.
        std::span<const std::uint64_t> answer;
        /// True: request() a save; the other carried writes wait for it.
        bool save = false;
    };
    /// A datagram left, the first to carry the writes `carried` (staging order); `changed`: it
    /// changed the image. The writes the file holds already (saved ahead of their production)
    /// are answered now. The others wait for a save when the image changed (a save is asked
    /// for) or when one is under way or asked for (it may hold the values they wrote: a write
    /// that changed nothing); else they are answered now too. `answer` views `carried`.
    Sent on_sent(std::span<const std::uint64_t> carried, bool changed);

    struct Saved {
        /// The sent writes this save answers, in staging order: `ok`; when it failed, `ok` but
        /// not saved (`saved: false`), with error().
        std::vector<std::uint64_t> answered;
        /// When it failed, the queued writes it held, never to be produced: those with an id in
        /// (refuse_after, refuse_through], to refuse (`not saved: ` error()). Empty otherwise.
        std::uint64_t refuse_after = 0;
        std::uint64_t refuse_through = 0;
        /// saved() or error() changed: the status says so.
        bool status_changed = false;
        /// The first save to succeed after saves failed.
        bool recovered = false;
    };
    /// The save under way is done: nullopt when the image is on disk, else why not.
    Saved on_saved(const std::optional<std::string>& error);

    /// While saves fail and none is under way: true, once every `retry_interval`, when a save is
    /// due at `now` (request() it). The first tick after a failure starts the interval.
    bool on_tick(MonoTime now);

    /// True when the file holds the image being produced, or a newer one.
    bool saved() const { return saved_; }
    /// True while a save is under way.
    bool saving() const { return in_flight_; }
    /// True when a save was asked for while one was under way: once on_saved() is handled
    /// (writes refused), request() it.
    bool again() const { return again_; }
    /// Why the last save failed; empty once one succeeds.
    const std::string& error() const { return error_; }
    /// Whether the file holds the staged write `write_id` (saved ahead of its production): a
    /// queued write taken out unproduced must then be taken out of the file too (save the image
    /// as produced).
    bool holds(std::uint64_t write_id) const { return write_id <= saved_through_; }

private:
    bool saved_;
    bool in_flight_ = false;
    bool again_ = false;
    std::uint64_t saved_through_ = 0;     ///< the last staged write the file holds
    std::uint64_t saving_through_ = 0;    ///< the last staged write of the save under way
    std::vector<std::uint64_t> saving_;   ///< sent writes the save under way answers
    std::vector<std::uint64_t> unsaved_;  ///< sent writes waiting for the next save
    std::vector<std::byte> projection_;   ///< what the save under way writes
    std::string error_;
    std::optional<MonoTime> retry_at_;
};

}  // namespace eip2mqtt::core::exchange
