// HeapPolicy: a plot canvas's pixmap, freed and made again at the same size, reuses the pages
// of the last one (before, glibc mapped each one afresh: ~900 page faults per first paint of a
// 1366 x 700 canvas). Skips where the C library has no such setting (AddressSanitizer's
// allocator, a libc other than glibc).

#include "HeapPolicy.h"

#include <QImage>
#include <QtTest>

#include <cstdlib>
#include <sys/resource.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

using namespace driftlab;

namespace {
long minorFaults()
{
    rusage r{};
    getrusage(RUSAGE_THREAD, &r);
    return r.ru_minflt;
}
} // namespace

class TestHeapPolicy : public QObject {
    Q_OBJECT
private slots:
    void initTestCase()
    {
        if (!HeapPolicy::keepLargeBlocksInHeap())
            QSKIP("this C library's allocator takes no mallopt() settings");
    }

    void aCanvasSizedImageMadeAgainReusesItsPages()
    {
        const QSize size(1366, 700); // 3.8 MB at 32 bits a pixel
        {
            QImage first(size, QImage::Format_ARGB32_Premultiplied);
            first.fill(Qt::white); // touches every page once
        }
        const long before = minorFaults();
        {
            QImage again(size, QImage::Format_ARGB32_Premultiplied);
            again.fill(Qt::black);
        }
        const long faults = minorFaults() - before;
        // 933 pages are touched; a fresh mapping faults on each of them.
        QVERIFY2(faults < 50, qPrintable(QStringLiteral("%1 page faults making the image again").arg(faults)));
    }

    void blocksUnderTheThresholdComeFromTheHeap()
    {
#if defined(__GLIBC__)
        const size_t mapped = mallinfo2().hblkhd;
        void *volatile p = std::malloc(4 << 20); // volatile: the compiler may not drop the pair
        QVERIFY(p != nullptr);
        QCOMPARE(mallinfo2().hblkhd, mapped); // not a mapping of its own
        std::free(p);
#endif
    }
};

QTEST_MAIN(TestHeapPolicy)
#include "tst_heappolicy.moc"
