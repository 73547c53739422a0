// A function written once here and, under other names, again in second.cpp: the duplicate
// finder must report the pair (ctest duplicate_finder_reports_a_copy).
int checksum(const unsigned char* bytes, int size) {
    int sum = 0;
    for (int i = 0; i < size; ++i) {
        sum += bytes[i];
        if (sum > 255) sum -= 255;
    }
    return sum == 0 ? 255 : sum;
}
