#include "cli.h"

int main(int argc, char **argv) {
    return armour::armour_main(argc, argv);
}
