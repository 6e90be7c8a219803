// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_query: narrow-phase queries from a text file (format and conversions in query_format.hpp).
//   xeno_query pairs.tsv                      -> one result line per pair on standard output
//   xeno_query --precision float < pairs.tsv  -> the same in float
// Bad lines are reported on standard error by line number and skipped.
// Exit status: 0 every line good, 1 some line bad, 2 bad command line or unreadable input (a
// missing file, a directory, a read error).
#include "query/query_format.hpp"

#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
    using namespace xeno::query;
    Options options;
    try {
        options = parse_options(argc, argv);
    } catch (const OptionsError& e) {
        std::cerr << "xeno_query: " << e.what() << "\nTry 'xeno_query --help'.\n";
        return 2;
    }
    if (options.help) {
        std::cout << usage();
        return 0;
    }
    std::ios::sync_with_stdio(false);
    int bad = 0;
    const bool standard_input = options.input.empty() || options.input == "-";
    try {
        if (standard_input) {
            bad = process(std::cin, std::cout, std::cerr, options.precision);
        } else {
            std::ifstream file(options.input);
            if (!file) {
                std::cerr << "xeno_query: cannot open '" << options.input << "'\n";
                return 2;
            }
            bad = process(file, std::cout, std::cerr, options.precision);
        }
    } catch (const ReadError& e) {
        std::cout.flush();
        std::cerr << "xeno_query: cannot read " << (standard_input ? std::string("standard input") : "'" + options.input + "'")
                  << ": " << e.what() << '\n';
        return 2;
    }
    std::cout.flush();
    if (!std::cout) {
        std::cerr << "xeno_query: could not write the results\n";
        return 2;
    }
    return bad > 0 ? 1 : 0;
}
