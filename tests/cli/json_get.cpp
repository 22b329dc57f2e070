// json_get FILE POINTER...: prints the JSON values at the given JSON pointers (RFC 6901), one
// per line: strings raw, everything else as compact JSON. Exit code 1 when a pointer is
// missing, 2 when the file is not JSON. Used by cli_test.sh, so the CLI tests need nothing
// beyond the project's own dependencies.

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: json_get FILE POINTER...\n";
        return 2;
    }
    std::ifstream in(argv[1]);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        std::cerr << "json_get: " << argv[1] << " is not JSON: " << e.what() << "\n";
        return 2;
    }
    int status = 0;
    for (int i = 2; i < argc; ++i) {
        try {
            const nlohmann::json& v = j.at(nlohmann::json::json_pointer(argv[i]));
            std::cout << (v.is_string() ? v.get<std::string>() : v.dump()) << "\n";
        } catch (const std::exception& e) {
            std::cerr << "json_get: " << argv[i] << ": " << e.what() << "\n";
            status = 1;
        }
    }
    return status;
}
