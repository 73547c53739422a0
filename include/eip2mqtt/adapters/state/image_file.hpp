#pragma once
/// One produced exchange's image file in the state directory (its bytes are described in
/// src/adapters/state/detail/image_format.hpp): two slots of 4 KiB, the newest image in one, a
/// save overwriting the other in place and fdatasyncing it. The file is created whole (written
/// to a temporary, fsynced, renamed, directory fsynced) only by the first save after the file
/// was missing, of another layout or of the format before slots; from then on it stays open,
/// so that neither a full disk (on file systems that overwrite in place: ext4, XFS, tmpfs) nor
/// a directory or file made read-only after that stops a save. A file removed while open is
/// noticed after the save that went to it, and created again at once.
///
/// Threading: constructed on the loop (it reads the file); save() runs on one thread at a time
/// (the ImagePersister's worker), never at the same time as another call.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::state {

class ImageFile {
public:
    /// Reads `path` now and keeps it open: the newest image of this layout (`fingerprint` and
    /// `length` bytes) from either format. A missing file or one of another layout is logged at
    /// info, one that cannot be read or checked at warn; either way loaded() is then empty.
    ImageFile(std::string path, std::string exchange, std::uint64_t fingerprint,
              std::size_t length);
    ~ImageFile();
    ImageFile(const ImageFile&) = delete;
    ImageFile& operator=(const ImageFile&) = delete;

    /// The image read at construction, when there was one of this layout.
    const std::optional<std::vector<std::byte>>& loaded() const { return loaded_; }
    /// True when the file read at construction was in the slotted format with loaded() as its
    /// newest image: saves overwrite a slot from the first one on.
    bool in_place() const { return in_place_; }
    const std::string& path() const { return path_; }

    /// Saves `data` (the layout's length) as the newest image, durably. nullopt on success;
    /// else what failed, with the file and the system's reason ("fdatasync /var/lib/eip2mqtt/
    /// sp.image: Input/output error"), and the newest image on disk is the one before.
    std::optional<std::string> save(std::span<const std::byte> data);

private:
    void read_existing();
    std::optional<std::string> save_in_place(std::span<const std::byte> data);
    std::optional<std::string> create(std::span<const std::byte> data);
    void close_file();

    std::string path_;
    std::string exchange_;
    std::uint64_t fingerprint_;
    std::size_t length_;
    std::optional<std::vector<std::byte>> loaded_;
    bool in_place_ = false;
    int fd_ = -1;                 ///< open for writing; -1: the next save creates the file
    std::uint64_t sequence_ = 0;  ///< of the newest slot
    std::size_t newest_ = 0;      ///< the slot holding the newest image
};

}  // namespace eip2mqtt::adapters::state
