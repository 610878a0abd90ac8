// footpoint-import FILE.step: the faces of a STEP file as footpoint `bspline_surface` definitions,
// one JSON document on standard output (step_import.hpp says what and what not: the faces are
// not trimmed). Post one to the service with, e.g.,
//   footpoint-import part.step | jq '.faces[0].definition' |
//     curl -s -H 'Content-Type: application/json' --data-binary @- localhost:8080/v1/geometries
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>

#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>

#include "step_import.hpp"

int main(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::printf(
        "usage: footpoint-import FILE.step\n"
        "Writes the faces of the STEP file as footpoint bspline_surface definitions (JSON on standard\n"
        "output): each face's underlying surface over its parameter rectangle, NOT trimmed by its\n"
        "boundary (docs/nurbs.md, \"STEP files\").\n");
    return 0;
  }
  if (argc != 2) {
    std::fprintf(stderr, "usage: footpoint-import FILE.step (--help for more)\n");
    return 2;
  }
  // Open CASCADE's messages (a STEP file's syntax errors, transfer statistics) to standard error:
  // standard output holds the JSON only.
  const Handle(Message_Messenger)& messenger = Message::DefaultMessenger();
  messenger->ChangePrinters().Clear();
  messenger->AddPrinter(new Message_PrinterOStream("cerr", false, Message_Warning));
  try {
    std::cout << footpoint::import::import_step(argv[1]).dump(1) << '\n';
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "footpoint-import: %s\n", e.what());
    return 1;
  }
}
