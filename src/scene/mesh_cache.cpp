// The mesh files a scene reads (15), each read once: from a regular file, as a texture is.
#include "scene/input_file.h"
#include "scene/mesh_file.h"

namespace rt {

MeshFileCache::Entry& MeshFileCache::load(const std::filesystem::path& resolved,
                                          std::vector<std::string>& notes) {
    const FileId id = regular_file_id(resolved);
    if (const auto known = entries_.find(id); known != entries_.end()) return known->second;
    const std::string name = resolved.string();
    Entry entry;
    {
        const std::string bytes = read_regular_file(resolved);
        entry.file = read_mesh_file(bytes, name);
    }  // the bytes are freed before the shapes are made, to lower the peak
    for (const std::string& note : entry.file.notes) notes.push_back(name + ": " + note);
    return entries_.emplace(id, std::move(entry)).first->second;
}

}  // namespace rt
