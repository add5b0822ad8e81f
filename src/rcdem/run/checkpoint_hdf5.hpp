#pragma once
// The checkpoint as an HDF5 file (docs/checkpoint.md, "The HDF5 file"): the sections of the binary
// format, each a group holding its columns as datasets named as the state's serialize() names
// them, each with its unit, so that h5py, h5dump or any HDF5 reader reads it. It is a lossless
// re-encoding of the binary image: the writer takes an image, the reader gives one back, and the
// image's checks (framing, CRC-32, every section's size) then apply to both formats alike.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rcdem/run/checkpoint.hpp"

namespace rcdem::io::checkpoint_detail {

struct Parsed;

// HDF5's format signature, the first bytes of an HDF5 file without a user block.
inline constexpr char kHdf5Signature[9] = "\x89HDF\r\n\x1a\n";

// rcdem's header in the file's first 512 bytes (an HDF5 user block, which every HDF5 reader skips):
// the magic, u32 version 1, u32 CRC-32 of every byte from byte 24 on, u64 the file's size, then a
// line of text. HDF5 1.10 can crash on damaged metadata, so a file is handed to it only once its
// size and checksum are right.
inline constexpr char kSealMagic[9] = "RCDEMHDF";
inline constexpr std::size_t kSealBytes = 512, kSealCovered = 24;

// Checks the header of the open file `fd` of `size` bytes against its contents; throws Reject
// ("truncated: ...", "checksum mismatch ...").
void check_seal(int fd, std::uint64_t size);

// Writes the checkpoint `image` to the new file `file` (an existing one is an error), naming each
// section's columns by `layout` (checkpoint_layout of the parts the image was encoded from).
// Throws Reject with the reason (HDF5's innermost message, e.g. "No space left on device").
void write_hdf5_checkpoint(const std::filesystem::path& file, const Parsed& image,
                           const std::vector<CheckpointColumn>& layout);

// The binary image of the HDF5 checkpoint `file`, whose size is `file_size` bytes; throws Reject
// for a file that is not one (not HDF5, not written by rcdem, a dataset's type or shape not its
// section's, more data than the file holds).
std::string read_hdf5_checkpoint(const std::filesystem::path& file, std::uint64_t file_size);

}  // namespace rcdem::io::checkpoint_detail
