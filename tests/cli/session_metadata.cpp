// session_metadata IN OUT POINTER VALUE: copies the session IN to OUT with the JSON value VALUE
// at POINTER (RFC 6901) in its metadata, creating the objects on the way. The file stays valid
// (checksums and all): this makes sessions whose metadata holds what sandtin itself would not
// write, for the CLI tests of how such data is refused.

#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>

#include "io/session_file.hpp"

int main(int argc, char** argv) {
    if (argc != 5) {
        std::cerr << "usage: session_metadata IN OUT POINTER VALUE\n";
        return 2;
    }
    try {
        sandtin::Session session = sandtin::load_session(argv[1]);
        nlohmann::json metadata = nlohmann::json::parse(session.metadata_json);
        metadata[nlohmann::json::json_pointer(argv[3])] = nlohmann::json::parse(argv[4]);
        session.metadata_json = metadata.dump();
        sandtin::save_session(argv[2], session);
    } catch (const std::exception& e) {
        std::cerr << "session_metadata: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
